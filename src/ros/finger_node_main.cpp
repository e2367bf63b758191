// finger_node: creates the private handle, builds the wrapper, spins. A bad parameter stops it with a message.
#include <iostream>
#include <string>

#include "pneumatic_finger/ros/finger_node.hpp"
#include "pneumatic_finger/ros/node_main.hpp"

int main(int argc, char** argv) {
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
  return pneumatic_finger::runNode<pneumatic_finger::FingerNode>(argc, argv, "finger_node",
                                                                  pneumatic_finger::nodeParameterSpecs());
}
