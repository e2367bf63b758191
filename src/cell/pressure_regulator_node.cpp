// pressure_regulator: the cell's simulated regulator (PressureRegulator) as a node. The same class runs as the
// nodelet pneumatic_finger/PressureRegulatorNodelet (src/ros/nodelets.cpp).
#include <ros/ros.h>

#include <cstdio>

#include "pneumatic_finger/cell/pressure_regulator.hpp"
#include "pneumatic_finger/core/parameters.hpp"

int main(int argc, char** argv) {
  // Line by line even into a pipe or a file, so that the nodes' lines of one cell interleave in time order.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  if (pneumatic_finger::printParametersIfAsked(argc, argv, pneumatic_finger::PressureRegulator::parameterSpecs())) {
    return 0;
  }
  ros::init(argc, argv, "pressure_regulator");
  ros::NodeHandle nh, pnh("~");
  try {
    pneumatic_finger::PressureRegulator regulator(nh, pnh);
    ros::spin();
  } catch (const pneumatic_finger::ParameterError& e) {
    ROS_FATAL("pressure_regulator: %s", e.what());
    return 2;
  }
  return 0;
}
