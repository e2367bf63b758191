// finger_node's parameters: their one definition (type, default, unit, range, meaning), which `finger_node
// --parameters` prints for the README, and their reading and checking from the private handle.
#pragma once

#include <ros/node_handle.h>

#include <string>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/pressure_input.hpp"
#include "pneumatic_finger/core/calibration_error.hpp"
#include "pneumatic_finger/core/tip_uncertainty.hpp"
#include "pneumatic_finger/description/finger_urdf.hpp"
#include "pneumatic_finger/ros/parameter_reader.hpp"

namespace pneumatic_finger {

/// The node's own parameters (besides the actuator keys of parameterSpecs()), printed by `finger_node --parameters`.
const std::vector<NodeParameterSpec>& nodeParameterSpecs();

/// Everything the node reads at start-up, validated.
struct NodeSettings {
  FingerParameters finger;
  TipUncertainty tip_uncertainty;  ///< the calibration's error bar (rosparam tip_uncertainty/*, or the gripper file's)
  CalibrationError calibration_error;  ///< how well the calibration followed its data (calibration_error/*, or the
                                       ///< gripper file's); empty: none recorded
  PressureRange range;  ///< the parameter file's range (or the gripper file's finger's), by the loader's one rule
  FingerUrdfOptions urdf;
  PressureInputSettings input;  ///< the input rules' settings (atmospheric_pa and max_gauge_pa follow finger, urdf)
  // The defaults of the node's own parameters (nodeParameterSpecs() shows these, the one definition).
  SolverKind solver = ModelOptions().solver;
  bool publish_tf = true;
  std::string gripper_file;
  double object_rate_hz = 30.0;
  double force_arrow_m_per_n = 0.2;  ///< rviz's contact force arrows: 20 cm per newton (the cell's 0.07 N: 13 mm)
  double transform_timeout_s = 1.0;  ///< as the pressure's stale_timeout_s: a second without news is a lost publisher
  std::string description_param = "robot_description", pressure_topic = "pressure", joint_states_topic = "joint_states",
              finger_state_topic = "finger_state", grasp_object_topic = "grasp_object";
  /// Volume as the input (docs/MODEL.md "Volume"): when set, the finger is driven by std_msgs/Float64 volumes (m^3)
  /// on this topic instead of pressures; empty (the default): by pressure.
  std::string volume_topic;
};

/// The actuator keys dynamic_reconfigure sets live (cfg/FingerNode.cfg's actuator group): besides a gripper file
/// they are a restarted node's previous live values, not a second definition.
inline bool isLiveActuatorKey(const std::string& key) {
  return key == "shear_modulus_pa" || key == "chamber_gap_m" || key == "base_wall_share" || key == "wall_locking_jm";
}

/// Reads and validates every parameter from the private handle.
/// @throws ParameterError naming the key, the value and what is allowed
NodeSettings readNodeSettings(const ros::NodeHandle& private_nh);

/// The one range check of a node number, at start-up and live (dynamic_reconfigure): @p x itself when allowed.
/// @throws ParameterError naming the key, the value and the allowed range
double checkNodeNumber(const std::string& key, double x);

}  // namespace pneumatic_finger
