// pressure_regulator: a simulated regulator for the cell. It fills the gripper's chambers the way the paper's
// constant-flow source does (regulator.hpp), holds the setpoint, and publishes the absolute pressure.
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <std_msgs/Float64.h>

#include <cmath>

#include "pneumatic_finger/core/regulator.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pf = pneumatic_finger;

int main(int argc, char** argv) {
  ros::init(argc, argv, "pressure_regulator");
  ros::NodeHandle nh, pnh("~");
  double flow = 0, rate_hz = 0, setpoint = 0;
  int finger_count = 0;
  std::string config;
  pnh.param("config", config, std::string());
  pnh.param("flow_m3_per_s", flow, 1.6e-5);  // about 1 L/min: fills three fingers to 2 kg/cm^2 in about 1 s
  pnh.param("finger_count", finger_count, 3);
  pnh.param("publish_rate_hz", rate_hz, 100.0);
  pf::FingerParameters finger;
  try {
    pf::RawParameterMap raw;
    if (!config.empty()) pf::loadRawParametersFromYamlFile(config, raw);
    finger = pf::FingerParameters::fromRaw(raw);
    if (!(flow > 0) || !std::isfinite(flow)) throw pf::ParameterError("parameter 'flow_m3_per_s' must be > 0");
    if (finger_count < 1) throw pf::ParameterError("parameter 'finger_count' must be >= 1");
    if (!(rate_hz > 0 && rate_hz <= 10000)) throw pf::ParameterError("parameter 'publish_rate_hz' must be in (0, 10000]");
  } catch (const pf::ParameterError& e) {
    ROS_FATAL("pressure_regulator: %s", e.what());
    return 2;
  }
  const double p_o = finger.atmospheric_pressure_pa;
  const double volume = pf::restVolumeM3(finger, finger_count);
  const double fill_rate = pf::fillRatePaPerS(flow, volume, p_o);
  ROS_INFO("pressure_regulator: V_o = %.3g m^3 (%d fingers), Q = %.3g m^3/s: %.0f Pa/s, 2 kg/cm^2 in %.2f s", volume,
           finger_count, flow, fill_rate, 196133.0 / fill_rate);
  double gauge = 0.0;
  ros::Subscriber sub = nh.subscribe<std_msgs::Float64>("setpoint", 10, [&setpoint](const std_msgs::Float64::ConstPtr& m) {
    if (std::isfinite(m->data) && m->data >= 0) setpoint = m->data;
    else ROS_WARN("pressure_regulator: refused setpoint %g Pa (must be a finite gauge pressure >= 0)", m->data);
  });
  ros::Publisher pub = nh.advertise<sensor_msgs::FluidPressure>("pressure", 10);
  ros::Rate rate(rate_hz);
  ros::Time last = ros::Time::now();
  sensor_msgs::FluidPressure msg;
  while (ros::ok()) {
    ros::spinOnce();
    const ros::Time now = ros::Time::now();
    gauge = pf::regulatorStep(gauge, setpoint, fill_rate, (now - last).toSec());
    last = now;
    msg.header.stamp = now;
    msg.fluid_pressure = gauge + p_o;
    pub.publish(msg);
    rate.sleep();
  }
  return 0;
}
