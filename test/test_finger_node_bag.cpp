// rostest (test/finger_node_bag.test): finger_node under a looping bag with simulated time. Every loop of the bag
// starts a new timeline (ROS time goes back 2 s); the node must keep publishing joint states on each one, with
// stamps from the bag, and report the jumps in diagnostics.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include <mutex>
#include <string>
#include <vector>
#include "ros_test_support.hpp"

namespace {

std::mutex g_mutex;
std::vector<double> g_stamps;  // joint_states stamps, in arrival order
long g_time_jumps = -1;

void onJoints(const sensor_msgs::JointState::ConstPtr& m) {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_stamps.push_back(m->header.stamp.toSec());
}

void onDiagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
  std::lock_guard<std::mutex> lock(g_mutex);
  for (const auto& s : m->status) {
    for (const auto& kv : s.values) {
      if (kv.key == "time jumps (new timeline)") g_time_jumps = std::stol(kv.value);
    }
  }
}

}  // namespace

TEST(FingerNodeBag, JointStatesOnEveryLoopOfABagPlayedWithClockAndLoop) {
  ros::NodeHandle nh;
  ros::Subscriber joints = nh.subscribe("joint_states", 10000, onJoints);
  ros::Subscriber diagnostics = nh.subscribe("/diagnostics", 100, onDiagnostics);
  // Until four loops have started (three jumps back) or 60 s of wall time.
  auto loops = [] {
    std::lock_guard<std::mutex> lock(g_mutex);
    std::vector<int> per_loop(1, 0);
    for (std::size_t i = 0; i < g_stamps.size(); ++i) {
      if (i > 0 && g_stamps[i] < g_stamps[i - 1]) per_loop.push_back(0);
      ++per_loop.back();
    }
    return per_loop;
  };
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(60);
  while (loops().size() < 4 && ros::WallTime::now() < deadline) ros::WallDuration(0.05).sleep();
  const std::vector<int> per_loop = loops();
  ASSERT_GE(per_loop.size(), 4u) << "joint states stopped after " << per_loop.size() << " loop(s) of the bag";
  // The loops in the middle are whole: most of the bag's 100 pressures became joint states on each of them (the
  // first and last are cut by when the test starts and stops).
  for (std::size_t k = 1; k + 1 < per_loop.size(); ++k) EXPECT_GE(per_loop[k], 50) << "loop " << k;
  // Stamps are the bag's own (100.00 .. 101.98 s), never the same instant twice within a loop.
  std::lock_guard<std::mutex> lock(g_mutex);
  for (std::size_t i = 0; i < g_stamps.size(); ++i) {
    EXPECT_GE(g_stamps[i], 100.0 - 1e-9);
    EXPECT_LE(g_stamps[i], 101.98 + 1e-9);
    if (i > 0 && g_stamps[i] >= g_stamps[i - 1]) {
      EXPECT_GT(g_stamps[i], g_stamps[i - 1]) << "no stamp twice, except across the jump back";
    }
  }
  EXPECT_GE(g_time_jumps, 1) << "diagnostics do not count the jumps back";
}

int main(int argc, char** argv) { return pf_test::runRosTests(argc, argv, "finger_node_bag_test", 1); }
