// The gripper's nodes as nodelets: a finger (FingerNode) and the cell's regulator (PressureRegulator), so that a
// gripper can run in one nodelet manager, the regulator's pressure reaching every finger without serialization.
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include <memory>

#include "pneumatic_finger/cell/pressure_regulator.hpp"
#include "pneumatic_finger/ros/finger_node.hpp"

namespace pneumatic_finger {

constexpr char kFingerNodeName[] = "finger_node";
constexpr char kPressureRegulatorName[] = "pressure_regulator";

/// A node class (built from the public and private handles) as a nodelet. A nodelet cannot exit its manager: a bad
/// parameter is said, with the node's name, and the nodelet does nothing (nothing wrong is published).
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

using FingerNodelet = NodeNodelet<FingerNode, kFingerNodeName>;
using PressureRegulatorNodelet = NodeNodelet<PressureRegulator, kPressureRegulatorName>;

}  // namespace pneumatic_finger

PLUGINLIB_EXPORT_CLASS(pneumatic_finger::FingerNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(pneumatic_finger::PressureRegulatorNodelet, nodelet::Nodelet)
