// The main() of every rostest binary: gtest, a ROS node of the given name, an AsyncSpinner so that subscriptions are
// served while a test waits, and a clean shutdown.
#pragma once

#include <gtest/gtest.h>
#include <ros/ros.h>

namespace pf_test {

inline int runRosTests(int argc, char** argv, const char* node_name, unsigned spinner_threads = 2) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, node_name);
  ros::AsyncSpinner spinner(spinner_threads);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  ros::shutdown();
  return result;
}

}  // namespace pf_test
