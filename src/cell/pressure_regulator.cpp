#include "pneumatic_finger/cell/pressure_regulator.hpp"

#include <sensor_msgs/FluidPressure.h>

#include <cmath>

#include "pneumatic_finger/core/regulator.hpp"
#include "pneumatic_finger/core/units.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "pneumatic_finger/ros/parameter_reader.hpp"

namespace pneumatic_finger {

const std::vector<NodeParameterSpec>& PressureRegulator::parameterSpecs() {
  static const std::vector<NodeParameterSpec> table = {
      textParameter("config", "", "empty, or a finger file (YAML)",
                    "the finger's parameter file, for its rest volume V_o and P_o (empty: the default finger)"),
      numberParameter("flow_m3_per_s", kCellRegulatorFlowM3PerS, 0, true, 1.0, "m^3/s",
                      "the source's constant flow Q (1.6e-5: about 1 L/min, three fingers to 2 kg/cm^2 in 1 s)"),
      integerParameter("finger_count", 3, 1, 64, "fingers the regulator fills (their chambers' volumes add)"),
      numberParameter("publish_rate_hz", 100.0, 0, true, 10000, "Hz", "how often the pressure is published"),
  };
  return table;
}

PressureRegulator::PressureRegulator(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
  const NodeParameterReader in(pnh, parameterSpecs());
  const std::string config = in.text("config");
  const double flow = in.number("flow_m3_per_s"), rate_hz = in.number("publish_rate_hz");
  const int finger_count = static_cast<int>(in.number("finger_count"));
  in.refuseUnknownKeys();
  RawParameterMap raw;
  if (!config.empty()) loadRawParametersFromYamlFile(config, raw);
  const FingerParameters finger = FingerParameters::fromRaw(raw);
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
