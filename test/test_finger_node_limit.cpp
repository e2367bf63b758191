// rostest: finger_node under the membrane wall law (test/finger_node_limit.test, config/marchese2015_ribbed.yaml). A
// pressure at or beyond the wall's limit point does not determine the shape: the node publishes no joint_states and no
// new shape, finger_state repeats the last one with STATUS_BEYOND_LIMIT_POINT, diagnostics WARN and say why; a pressure
// below the limit brings the shape back.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/JointState.h>

#include <mutex>
#include <string>
#include <vector>

#include "pneumatic_finger/FingerModelState.h"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "ros_test_support.hpp"

namespace pf = pneumatic_finger;

namespace {

std::mutex mutex;
std::vector<sensor_msgs::JointState> joints;
std::vector<pf::FingerModelState> states;
std::vector<diagnostic_msgs::DiagnosticStatus> diagnostics;

template <class T>
std::size_t countOf(const std::vector<T>& v) {
  std::lock_guard<std::mutex> lock(mutex);
  return v.size();
}

template <class T>
T lastOf(const std::vector<T>& v) {
  std::lock_guard<std::mutex> lock(mutex);
  return v.back();
}

// Waits (wall time) until @p done holds, or @p seconds pass.
template <class F>
bool waitFor(F done, double seconds) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(seconds);
  while (!done() && ros::WallTime::now() < deadline) ros::WallDuration(0.01).sleep();
  return done();
}

void onJoints(const sensor_msgs::JointState::ConstPtr& m) {
  std::lock_guard<std::mutex> lock(mutex);
  joints.push_back(*m);
}

void onState(const pf::FingerModelState::ConstPtr& m) {
  std::lock_guard<std::mutex> lock(mutex);
  states.push_back(*m);
}

void onDiagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
  std::lock_guard<std::mutex> lock(mutex);
  for (const auto& s : m->status) {
    if (s.name.find("pressure input") != std::string::npos) diagnostics.push_back(s);
  }
}

pf::FingerModel ribbedModel() {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/marchese2015_ribbed.yaml", raw);
  return pf::FingerModel(pf::FingerParameters::fromRaw(raw));
}

}  // namespace

TEST(FingerNodeLimitPoint, NothingIsPublishedPastTheLimitPointAndTheShapeReturnsBelowIt) {
  ros::NodeHandle nh;
  const ros::Subscriber sub_j = nh.subscribe("joint_states", 100, onJoints);
  const ros::Subscriber sub_s = nh.subscribe("finger_state", 100, onState);
  const ros::Subscriber sub_d = nh.subscribe("/diagnostics", 100, onDiagnostics);
  ros::Publisher pub = nh.advertise<sensor_msgs::FluidPressure>("pressure", 10);
  ASSERT_TRUE(waitFor([&] { return pub.getNumSubscribers() > 0 && sub_j.getNumPublishers() > 0; }, 30));
  const pf::FingerModel model = ribbedModel();
  const double limit = model.limitGaugePa();
  ASSERT_TRUE(std::isfinite(limit)) << "the ribbed segment's Neo-Hookean wall has a limit point";
  auto send = [&pub](double gauge_pa) {
    sensor_msgs::FluidPressure m;
    m.header.stamp = ros::Time::now();
    m.fluid_pressure = gauge_pa + pf_test::kAtm;
    pub.publish(m);
  };

  // Below the limit: the model's shape.
  send(0.8 * limit);
  ASSERT_TRUE(waitFor([] { return countOf(joints) > 0; }, 10));
  pf::FingerWorkspace ws(model);
  const pf::FingerState& below = model.evaluate(0.8 * limit, ws);
  const sensor_msgs::JointState shown = lastOf(joints);
  for (int i = 0; i < model.chamberCount(); ++i) EXPECT_NEAR(shown.position[i], below.joint_angle_rad[i], 1e-12);
  const pf::FingerModelState shape = lastOf(states);
  EXPECT_EQ(shape.status, pf::FingerModelState::STATUS_OK);

  // At and beyond it: finger_state repeats the last shape and says why; no joint_states.
  const std::size_t joints_before = countOf(joints), states_before = countOf(states);
  for (double share : {1.0, 1.3}) {
    send(share * limit);
    ros::WallDuration(0.05).sleep();
  }
  ASSERT_TRUE(waitFor([&] { return countOf(states) >= states_before + 2; }, 10));
  ros::WallDuration(0.5).sleep();
  EXPECT_EQ(countOf(joints), joints_before) << "joint_states published past the limit point";
  const pf::FingerModelState past = lastOf(states);
  EXPECT_EQ(past.status, pf::FingerModelState::STATUS_BEYOND_LIMIT_POINT);
  EXPECT_EQ(past.gauge_pa, shape.gauge_pa) << "the repeated shape keeps its own pressure";
  EXPECT_EQ(past.joint_angle_rad, shape.joint_angle_rad);
  EXPECT_EQ(past.tip_angle_rad, shape.tip_angle_rad);
  ASSERT_TRUE(waitFor(
      [] {
        if (countOf(diagnostics) == 0) return false;
        const auto d = lastOf(diagnostics);
        return d.message.find("limit point") != std::string::npos;
      },
      5));
  EXPECT_EQ(lastOf(diagnostics).level, diagnostic_msgs::DiagnosticStatus::WARN);

  // Below it again: a new shape.
  send(0.5 * limit);
  ASSERT_TRUE(waitFor([&] { return countOf(joints) > joints_before; }, 10));
  EXPECT_EQ(lastOf(states).status, pf::FingerModelState::STATUS_OK);
  EXPECT_LT(lastOf(joints).position[0], shown.position[0]);
}

int main(int argc, char** argv) { return pf_test::runRosTests(argc, argv, "finger_node_limit_test", 2); }
