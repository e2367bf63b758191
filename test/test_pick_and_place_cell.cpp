// rostest: the pick-and-place cell, headless (test/pick_and_place_cell.test starts it).
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <std_msgs/UInt32.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <set>
#include "ros_test_main.hpp"

namespace {

const std::vector<std::string> kTips = {"finger_a_tip", "finger_b_tip", "finger_c_tip"};

struct Recorder {
  std::mutex mutex;
  std::map<std::string, std::set<std::string>> frame_publishers;
  std::atomic<unsigned> cycles{0};
  std::atomic<double> gauge_pa{0.0};
  void onTf(const ros::MessageEvent<tf2_msgs::TFMessage const>& e) {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& t : e.getMessage()->transforms) frame_publishers[t.child_frame_id].insert(e.getPublisherName());
  }
};

}  // namespace

TEST(PickAndPlaceCell, RunsACycleWithFingertipsClosingAndOpeningAndOneAuthorityPerFrame) {
  ros::NodeHandle nh;
  Recorder rec;
  tf2_ros::Buffer buffer(ros::Duration(60));
  tf2_ros::TransformListener listener(buffer);
  auto s1 = nh.subscribe("/tf", 1000, &Recorder::onTf, &rec);
  auto s2 = nh.subscribe("/tf_static", 100, &Recorder::onTf, &rec);
  auto s3 = nh.subscribe<std_msgs::UInt32>("/cell/cycles", 10, boost::function<void(const std_msgs::UInt32::ConstPtr&)>(
                                                                   [&rec](const std_msgs::UInt32::ConstPtr& m) { rec.cycles = m->data; }));
  auto s4 = nh.subscribe<sensor_msgs::FluidPressure>(
      "/gripper/pressure", 100, boost::function<void(const sensor_msgs::FluidPressure::ConstPtr&)>(
                                    [&rec](const sensor_msgs::FluidPressure::ConstPtr& m) { rec.gauge_pa = m->fluid_pressure - 101325.0; }));

  // Every fingertip resolves from world.
  for (const auto& tip : kTips) {
    std::string error;
    EXPECT_TRUE(buffer.canTransform("world", tip, ros::Time(0), ros::Duration(30), &error)) << tip << ": " << error;
  }
  // Radial distance of each tip from the gripper axis (tool0's z), sampled with the regulator's pressure,
  // through one whole cycle.
  auto radial = [&](const std::string& tip) {
    const auto t = buffer.lookupTransform("tool0", tip, ros::Time(0));
    return std::hypot(t.transform.translation.x, t.transform.translation.y);
  };
  std::map<std::string, double> open_before, closed, open_after;
  double max_gauge = 0;
  bool was_inflated = false;
  const ros::Time deadline = ros::Time::now() + ros::Duration(60);
  // Until a cycle has completed and each tip was seen open, closed and open again (the test may start mid-cycle, so
  // the first open sample can come from the second cycle).
  auto seen_all = [&] {
    for (const auto& tip : kTips) {
      if (!open_before.count(tip) || !closed.count(tip) || !open_after.count(tip)) return false;
    }
    return true;
  };
  while (ros::Time::now() < deadline && (rec.cycles < 1 || !seen_all())) {
    const double p = rec.gauge_pa;
    for (const auto& tip : kTips) {
      const double r = radial(tip);
      if (p < 1.0 && !was_inflated && !open_before.count(tip)) open_before[tip] = r;
      if (p > max_gauge - 1.0) closed[tip] = r;  // at the highest pressure seen so far
      if (p < 1.0 && was_inflated && open_before.count(tip)) open_after[tip] = r;
    }
    max_gauge = std::max(max_gauge, p);
    was_inflated = was_inflated || (p > 100000.0 && !open_before.empty());
    ros::Duration(0.02).sleep();
  }
  EXPECT_GE(rec.cycles.load(), 1u) << "the cell did not complete a cycle in 60 s";
  EXPECT_GT(max_gauge, 100000.0) << "the regulator never inflated";
  for (const auto& tip : kTips) {
    ASSERT_TRUE(open_before.count(tip) && closed.count(tip) && open_after.count(tip)) << tip;
    // Closing: the 1.5 kg/cm^2 grasp brings the tips from 35 mm off the axis to within a few mm of it.
    EXPECT_LT(closed[tip], open_before[tip] - 0.02) << tip;
    // Opening: back to where it started (the straight finger), to rounding.
    EXPECT_NEAR(open_after[tip], open_before[tip], 1e-9) << tip;
  }
  // One authority per frame, and every finger frame and arm frame seen.
  std::lock_guard<std::mutex> lock(rec.mutex);
  for (const auto& f : rec.frame_publishers) {
    EXPECT_EQ(f.second.size(), 1u) << f.first << " has " << f.second.size() << " publishers";
  }
  for (const std::string frame : {"base_link", "tool0", "finger_a_segment_7", "finger_b_tip", "finger_c_segment_0"}) {
    EXPECT_TRUE(rec.frame_publishers.count(frame)) << frame;
  }
}

int main(int argc, char** argv) { return pf_test::runRosTests(argc, argv, "pick_and_place_cell_test", 2); }
