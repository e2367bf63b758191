// Every node's main, one way: line-buffered output, `--parameters` without a master, a node object built from the
// handles, a clear exit on a bad parameter.
#pragma once

#include <ros/ros.h>

#include <cstdio>
#include <exception>
#include <iostream>
#include <vector>

#include "pneumatic_finger/ros/parameter_reader.hpp"

namespace pneumatic_finger {

/// Runs @p Node as the node @p name: stdout line by line even into a pipe or a file (so that the lines of a cell's
/// nodes interleave in time order); `NODE --parameters` prints @p specs as Markdown for docs/ with no master; then
/// ros::init, Node(nh, private nh), and callbacks on @p threads threads (1: ros::spin on this one) until shutdown.
/// Whatever the construction throws (a ParameterError naming the key) is logged FATAL and written to stderr, and the exit code is 2.
template <class Node>
int runNode(int argc, char** argv, const char* name, const std::vector<NodeParameterSpec>& specs, int threads = 1) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  if (printParametersIfAsked(argc, argv, specs)) return 0;
  ros::init(argc, argv, name);
  ros::NodeHandle nh, pnh("~");
  try {
    Node node(nh, pnh);
    if (threads <= 1) {
      ros::spin();
    } else {
      ros::AsyncSpinner spinner(threads);
      spinner.start();
      ros::waitForShutdown();
    }
  } catch (const std::exception& e) {
    ROS_FATAL("%s: %s", name, e.what());
    std::cerr << name << ": error: " << e.what() << std::endl;  // also where a launch file's output="log" hides it
    return 2;
  }
  return 0;
}

}  // namespace pneumatic_finger
