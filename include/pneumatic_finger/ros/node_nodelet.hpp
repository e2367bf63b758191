// A node class as a nodelet: any of the package's node classes (built from the public and private handles) runs in a
// nodelet manager unchanged. Each layer registers its own: src/ros/nodelets.cpp the finger, src/cell/cell_nodelets.cpp
// the cell's regulator.
#pragma once

#include <nodelet/nodelet.h>

#include <memory>

#include "pneumatic_finger/core/parameters.hpp"

namespace pneumatic_finger {

/// @p Node as a nodelet named @p kName in its messages. A nodelet cannot exit its manager: a bad parameter is said,
/// with the node's name, and the nodelet does nothing (nothing wrong is published).
template <class Node, const char* kName>
class NodeNodelet : public nodelet::Nodelet {
  void onInit() override {
    try {
      node_ = std::make_unique<Node>(getNodeHandle(), getPrivateNodeHandle());
    } catch (const ParameterError& e) {
      NODELET_FATAL("%s: %s", kName, e.what());
    }
  }
  std::unique_ptr<Node> node_;
};

}  // namespace pneumatic_finger
