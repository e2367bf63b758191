#include "pneumatic_finger/cell/pressure_regulator.hpp"

#include <sensor_msgs/FluidPressure.h>

#include <cmath>

#include "pneumatic_finger/core/regulator.hpp"
#include "pneumatic_finger/core/units.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pneumatic_finger {

PressureRegulator::PressureRegulator(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
  double flow = 0, rate_hz = 0;
  int finger_count = 0;
  std::string config;
  pnh.param("config", config, std::string());
  pnh.param("flow_m3_per_s", flow, 1.6e-5);  // about 1 L/min: fills three fingers to 2 kg/cm^2 in about 1 s
  pnh.param("finger_count", finger_count, 3);
  pnh.param("publish_rate_hz", rate_hz, 100.0);
  RawParameterMap raw;
  if (!config.empty()) loadRawParametersFromYamlFile(config, raw);
  const FingerParameters finger = FingerParameters::fromRaw(raw);
  if (!(flow > 0) || !std::isfinite(flow)) throw ParameterError("parameter 'flow_m3_per_s' must be > 0");
  if (finger_count < 1) throw ParameterError("parameter 'finger_count' must be >= 1");
  if (!(rate_hz > 0 && rate_hz <= 10000)) throw ParameterError("parameter 'publish_rate_hz' must be in (0, 10000]");
  p_o_ = finger.atmospheric_pressure_pa;
  const double volume = restVolumeM3(finger, finger_count);
  fill_rate_pa_per_s_ = fillRatePaPerS(flow, volume, p_o_);
  ROS_INFO("pressure_regulator: V_o = %.3g m^3 (%d fingers), Q = %.3g m^3/s: %.0f Pa/s, 2 kg/cm^2 in %.2f s", volume,
           finger_count, flow, fill_rate_pa_per_s_, 2 * kPaPerKgfPerCm2 / fill_rate_pa_per_s_);
  setpoint_sub_ = nh.subscribe("setpoint", 10, &PressureRegulator::onSetpoint, this);
  pressure_pub_ = nh.advertise<sensor_msgs::FluidPressure>("pressure", 10);
  last_ = ros::Time::now();
  timer_ = nh.createTimer(ros::Duration(1.0 / rate_hz), &PressureRegulator::onTimer, this);
}

void PressureRegulator::onSetpoint(const std_msgs::Float64::ConstPtr& m) {
  if (std::isfinite(m->data) && m->data >= 0) {
    setpoint_pa_ = m->data;
  } else {
    ROS_WARN("pressure_regulator: refused setpoint %g Pa (must be a finite gauge pressure >= 0)", m->data);
  }
}

void PressureRegulator::onTimer(const ros::TimerEvent&) {
  const ros::Time now = ros::Time::now();
  gauge_pa_ = regulatorStep(gauge_pa_, setpoint_pa_, fill_rate_pa_per_s_, (now - last_).toSec());
  last_ = now;
  // A new message each time, published as a shared pointer: in a nodelet manager the finger nodelets receive it
  // without a copy or serialization.
  auto msg = boost::make_shared<sensor_msgs::FluidPressure>();
  msg->header.stamp = now;
  msg->fluid_pressure = gauge_pa_ + p_o_;
  pressure_pub_.publish(msg);
}

}  // namespace pneumatic_finger
