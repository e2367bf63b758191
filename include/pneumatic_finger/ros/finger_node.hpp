// The ROS wrapper: regulator pressure in; joint states, tf, the finger's state, diagnostics and a URDF out.
// All modelling is the core's (FingerModel, fingerUrdf); this class only reads parameters and moves messages.
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include <memory>
#include <string>
#include <vector>

#include "pneumatic_finger/FingerModelState.h"
#include "pneumatic_finger/FingerNodeConfig.h"
#include "pneumatic_finger/PressureForTipAngle.h"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/pressure_input.hpp"
#include "pneumatic_finger/description/finger_urdf.hpp"

namespace pneumatic_finger {

/// The node's own parameters (besides the actuator keys of parameterSpecs()): one definition of each (type,
/// default, unit, range, meaning), read by readNodeSettings() and printed by `finger_node --parameters` for the README.
struct NodeParameterSpec {
  std::string key;
  std::string type;           ///< "string", "double", "double[3]", "bool"
  std::string default_text;   ///< the default as text (strings, triples)
  double default_value;       ///< the default of a "double"
  double min_value;           ///< range of a "double" (of every entry of a "double[3]": |x| <= max_value)
  bool min_open;              ///< whether min_value itself is excluded
  double max_value;
  std::string unit;
  std::string allowed;        ///< the range as text (generated for numbers)
  std::string description;
};
const std::vector<NodeParameterSpec>& nodeParameterSpecs();

/// Everything the node reads at start-up, validated.
struct NodeSettings {
  FingerParameters finger;
  FingerUrdfOptions urdf;
  PressureInputSettings input;  ///< the input rules' settings (atmospheric_pa and max_gauge_pa follow finger, urdf)
  SolverKind solver;
  bool publish_tf = true;
  std::string gripper_file;
  std::string description_param, pressure_topic, joint_states_topic, finger_state_topic;
};

/// Reads and validates every parameter from the private handle.
/// @throws ParameterError naming the key, the value and what is allowed
NodeSettings readNodeSettings(const ros::NodeHandle& private_nh);

class FingerNode {
 public:
  /// Publishes the URDF and the static frames and starts listening. @throws ParameterError on a bad parameter.
  FingerNode(ros::NodeHandle& nh, ros::NodeHandle& private_nh);

 private:
  void onPressure(const sensor_msgs::FluidPressure::ConstPtr& msg);
  bool onInverse(PressureForTipAngle::Request& req, PressureForTipAngle::Response& res);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);
  void onReconfigure(FingerNodeConfig& config, uint32_t level);
  /// The live values as the node has them (chamber 1's for per-chamber keys).
  FingerNodeConfig currentConfig() const;
  /// Builds the model and publishes the URDF from settings_ (at start-up, and when the actuator is reconfigured).
  void buildModel(ros::NodeHandle& nh);
  void publish(const FingerState& state, const ros::Time& stamp, bool clamped);

  NodeSettings settings_;
  std::unique_ptr<FingerModel> model_;
  ros::Subscriber pressure_sub_;
  ros::Publisher joint_states_pub_, finger_state_pub_;
  ros::ServiceServer inverse_srv_;
  // Made only with publish_tf: without it the node does not even advertise /tf and /tf_static.
  std::unique_ptr<tf2_ros::TransformBroadcaster> tf_;
  std::unique_ptr<tf2_ros::StaticTransformBroadcaster> static_tf_;
  diagnostic_updater::Updater diagnostics_;
  ros::WallTimer diagnostics_timer_;

  // Preallocated outgoing messages: the per-message cycle fills them in place.
  sensor_msgs::JointState joint_states_;
  FingerModelState finger_state_;
  std::vector<geometry_msgs::TransformStamped> transforms_;

  // The input rules (stamps, time jumps, clamping, throttling, staleness) and their counters: ROS-free, in the core.
  PressureInputPolicy input_;

  // dynamic_reconfigure: the calibrated parameters and the input rates, validated like rosparams, applied live.
  std::unique_ptr<dynamic_reconfigure::Server<FingerNodeConfig>> reconfigure_;
  bool reconfigure_synced_ = false;
  ros::NodeHandle nh_;
};

}  // namespace pneumatic_finger
