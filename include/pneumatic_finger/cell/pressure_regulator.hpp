// The cell's simulated pressure regulator as a ROS class (used by the pressure_regulator node and nodelet): it fills
// the gripper's chambers the way the paper's constant-flow source does (core/regulator.hpp), holds the setpoint, and
// publishes the absolute pressure on a timer.
#pragma once

#include <ros/ros.h>
#include <std_msgs/Float64.h>

#include <vector>

#include "pneumatic_finger/ros/parameter_reader.hpp"

namespace pneumatic_finger {

class PressureRegulator {
 public:
  /// Reads ~config, ~flow_m3_per_s, ~finger_count, ~publish_rate_hz. @throws ParameterError naming a bad one.
  PressureRegulator(ros::NodeHandle& nh, ros::NodeHandle& private_nh);
  /// Its parameters' one definition (`pressure_regulator --parameters`).
  static const std::vector<NodeParameterSpec>& parameterSpecs();

 private:
  void onSetpoint(const std_msgs::Float64::ConstPtr& m);
  void onTimer(const ros::TimerEvent& e);

  double p_o_ = 0.0, fill_rate_pa_per_s_ = 0.0, gauge_pa_ = 0.0, setpoint_pa_ = 0.0;
  ros::Time last_;
  ros::Subscriber setpoint_sub_;
  ros::Publisher pressure_pub_;
  ros::Timer timer_;
};

}  // namespace pneumatic_finger
