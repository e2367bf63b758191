// finger_node: creates the private handle, builds the wrapper, spins. A bad parameter stops it with a message.
#include <ros/ros.h>

#include <cstdio>
#include <iostream>
#include <string>

#include "pneumatic_finger/ros/finger_node.hpp"

int main(int argc, char** argv) {
  // Line by line even into a pipe or a file, so that the nodes' lines of one cell interleave in time order.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  // `finger_node --parameters`: the node's own parameters as Markdown, for docs/ (no ROS master needed).
  if (pneumatic_finger::printParametersIfAsked(argc, argv, pneumatic_finger::nodeParameterSpecs())) return 0;
  // --help answers at once, as the other tools do, instead of waiting for a master.
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") {
      std::cout << "finger_node: the pneumatic finger's live twin. Subscribes to the regulator's pressure\n"
                << "(sensor_msgs/FluidPressure, absolute Pa) and publishes joint_states, tf and finger_state.\n\n"
                << "Usage: rosrun pneumatic_finger finger_node [__name:=NAME] [_PARAMETER:=VALUE ...]\n"
                << "   or: roslaunch pneumatic_finger finger.launch [ARG:=VALUE ...]\n\n"
                << "  --parameters  print the node's parameters (name, default, range, meaning) as Markdown\n"
                << "  -h, --help    print this help and exit\n\n"
                << "Topics, services and parameters: the package's README.md, \"The node: finger_node\".\n";
      return 0;
    }
  }
  ros::init(argc, argv, "finger_node");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  try {
    pneumatic_finger::FingerNode node(nh, private_nh);
    ros::spin();
  } catch (const pneumatic_finger::ParameterError& e) {
    ROS_FATAL("finger_node: %s", e.what());
    std::cerr << "finger_node: error: " << e.what() << std::endl;
    return 2;
  }
  return 0;
}
