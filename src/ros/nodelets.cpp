// The gripper's nodes as nodelets: a finger (FingerNode) and the cell's regulator (PressureRegulator), so that a
// gripper can run in one nodelet manager, the regulator's pressure reaching every finger without serialization.
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include <memory>

#include "pneumatic_finger/cell/pressure_regulator.hpp"
#include "pneumatic_finger/ros/finger_node.hpp"

namespace pneumatic_finger {

class FingerNodelet : public nodelet::Nodelet {
  void onInit() override {
    try {
      node_ = std::make_unique<FingerNode>(getNodeHandle(), getPrivateNodeHandle());
    } catch (const ParameterError& e) {
      // A nodelet cannot exit its manager: it says why and does nothing (nothing wrong is published).
      NODELET_FATAL("finger_node: %s", e.what());
    }
  }
  std::unique_ptr<FingerNode> node_;
};

class PressureRegulatorNodelet : public nodelet::Nodelet {
  void onInit() override {
    try {
      regulator_ = std::make_unique<PressureRegulator>(getNodeHandle(), getPrivateNodeHandle());
    } catch (const ParameterError& e) {
      NODELET_FATAL("pressure_regulator: %s", e.what());
    }
  }
  std::unique_ptr<PressureRegulator> regulator_;
};

}  // namespace pneumatic_finger

PLUGINLIB_EXPORT_CLASS(pneumatic_finger::FingerNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(pneumatic_finger::PressureRegulatorNodelet, nodelet::Nodelet)
