// What every rostest binary shares: its main() (gtest, a ROS node of the given name, an AsyncSpinner so that
// subscriptions are served while a test waits, a clean shutdown), the package's calibrated finger, and P_o.
#pragma once

#include <gtest/gtest.h>
#include <ros/ros.h>

#include <string>

#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/units.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pf_test {

/// The standard atmosphere the package's finger and the tests' regulators assume (Pa).
constexpr double kAtm = pneumatic_finger::kStandardAtmospherePa;

inline int runRosTests(int argc, char** argv, const char* node_name, unsigned spinner_threads = 2) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, node_name);
  ros::AsyncSpinner spinner(spinner_threads);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  ros::shutdown();
  return result;
}

#ifdef PACKAGE_SOURCE_DIR
/// The package's calibrated finger, config/finger.yaml, as the node under test loads it.
inline pneumatic_finger::FingerParameters packageParameters() {
  pneumatic_finger::RawParameterMap raw;
  pneumatic_finger::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/finger.yaml", raw);
  return pneumatic_finger::FingerParameters::fromRaw(raw);
}
#endif

}  // namespace pf_test
