// rostest: the pick-and-place cell, headless (test/pick_and_place_cell.test starts it).
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <std_msgs/String.h>
#include <std_msgs/UInt32.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <Eigen/Geometry>
#include <geometric_shapes/body_operations.h>
#include <geometric_shapes/shape_operations.h>

#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <set>
#include "pneumatic_finger/FingerModelState.h"
#include "pneumatic_finger/GraspObject.h"
#include "cell_watch.hpp"
#include "ros_test_support.hpp"

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
    was_inflated = was_inflated || (p > 50000.0 && !open_before.empty());
    ros::Duration(0.02).sleep();
  }
  EXPECT_GE(rec.cycles.load(), 1u) << "the cell did not complete a cycle in 60 s";
  EXPECT_GT(max_gauge, 50000.0) << "the regulator never inflated";
  for (const auto& tip : kTips) {
    ASSERT_TRUE(open_before.count(tip) && closed.count(tip) && open_after.count(tip)) << tip;
    // Closing on the 16 mm cylinder: the tips come from 35 mm off the axis by more than 10 mm, and stop at the
    // object's surface instead of passing through it (the lift test below checks every backbone point).
    EXPECT_LT(closed[tip], open_before[tip] - 0.01) << tip;
    EXPECT_GT(closed[tip], 0.016 - 0.0005) << tip;
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

// During the lift the object hangs in the gripper: every finger touches it (some backbone point within 1 mm of its
// surface) and none is inside it by more than 0.5 mm. The reference is independent of the node's planar solve:
// geometric_shapes' 3D body of the grasp_object message, in each finger's frame by tf, padded by +1 mm and -0.5 mm.
TEST(PickAndPlaceCell, DuringTheLiftEveryFingerTouchesTheObjectAndNoneEntersIt) {
  ros::NodeHandle nh;
  tf2_ros::Buffer buffer(ros::Duration(60));
  tf2_ros::TransformListener listener(buffer);
  pf_test::CellWatch watch(nh);
  int checked = 0;
  const ros::Time deadline = ros::Time::now() + ros::Duration(60);
  bool lifted = false;
  std::string last_phase;
  while (ros::Time::now() < deadline) {
    const pf_test::CellWatch::Snapshot now = watch.snapshot();
    const std::string& now_phase = now.phase;
    const auto& obj = now.object;
    const auto& now_states = now.states;
    if (now_phase != "lift") {
      last_phase = now_phase;
      // A whole lift seen, and enough of it: a short cycle's lift lasts 0.2 s, so its checks may take several lifts.
      if (lifted && checked > 5) break;
      ros::Duration(0.01).sleep();
      continue;
    }
    if (!lifted || now_phase != last_phase) {
      // The lift just began: the object's message (the sequencer judges the grasp as the lift begins) travels on its
      // own topic and may arrive a moment after the phase's.
      last_phase = now_phase;
      lifted = true;
      ros::Duration(0.05).sleep();
      continue;
    }
    ASSERT_TRUE(obj);
    ASSERT_EQ(obj->header.frame_id, "tool0") << "the object is not carried during the lift";
    ASSERT_EQ(now_states.size(), 3u);
    std::unique_ptr<shapes::Shape> shape(shapes::constructShapeFromMsg(obj->shape));
    ASSERT_TRUE(shape);
    std::unique_ptr<bodies::Body> body(bodies::createBodyFromShape(shape.get()));
    for (const auto& fs : now_states) {
      const std::string frame = fs.first + "_segment_0";
      const auto t = buffer.lookupTransform(frame, obj->header.frame_id, ros::Time(0), ros::Duration(1)).transform;
      const Eigen::Isometry3d finger_from_tool =
          Eigen::Translation3d(t.translation.x, t.translation.y, t.translation.z) *
          Eigen::Quaterniond(t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z);
      const auto& p = obj->pose;
      body->setPose(finger_from_tool * (Eigen::Translation3d(p.position.x, p.position.y, p.position.z) *
                                        Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y,
                                                           p.orientation.z)));
      // Points along the whole backbone, 50 per segment.
      std::vector<Eigen::Vector3d> points;
      const auto& bb = fs.second->backbone;
      for (std::size_t i = 0; i + 1 < bb.size(); ++i) {
        for (int k = 0; k <= 50; ++k) {
          const double u = k / 50.0;
          points.emplace_back(bb[i].x + u * (bb[i + 1].x - bb[i].x), bb[i].y + u * (bb[i + 1].y - bb[i].y), 0.0);
        }
      }
      body->setPadding(-0.0005);
      for (const auto& q : points) {
        EXPECT_FALSE(body->containsPoint(q)) << fs.first << ": (" << q.x() << ", " << q.y()
                                             << ") is more than 0.5 mm inside the object";
      }
      body->setPadding(0.001);
      bool near = false;
      for (const auto& q : points) near = near || body->containsPoint(q);
      EXPECT_TRUE(near) << fs.first << " does not touch the object (no backbone point within 1 mm of it)";
      EXPECT_EQ(fs.second->object_status, pneumatic_finger::FingerModelState::OBJECT_TOUCHING) << fs.first;
      // A grasp, not a pinch: every contact lies on the cylinder's side, at least 5 mm from either rim.
      const auto& dims = obj->shape.dimensions;  // CYLINDER_HEIGHT, CYLINDER_RADIUS
      const Eigen::Isometry3d finger_from_object = finger_from_tool * (Eigen::Translation3d(p.position.x, p.position.y,
                                                   p.position.z) * Eigen::Quaterniond(p.orientation.w, p.orientation.x,
                                                   p.orientation.y, p.orientation.z));
      for (const auto& c : fs.second->contact_points) {
        const Eigen::Vector3d in_object = finger_from_object.inverse() * Eigen::Vector3d(c.x, c.y, c.z);
        EXPECT_LT(std::fabs(in_object.z()), 0.5 * dims[0] - 0.005) << fs.first << ": a contact near a rim";
        EXPECT_NEAR(std::hypot(in_object.x(), in_object.y()), dims[1], 0.001) << fs.first << ": not on the side";
      }
      body->setPadding(0.0);
    }
    ++checked;
    ros::Duration(0.05).sleep();
  }
  EXPECT_GT(checked, 5) << "the lift was not observed";
  // A light object (config/cell.yaml's 10 g, or the launch's object_mass): carried because the grip's friction holds
  // its weight and the lift's inertia, and the event says so with the numbers.
  double mass_kg = 0.0;
  ASSERT_TRUE(ros::param::get("/cell_sequencer/object_mass_kg", mass_kg));
  std::ostringstream weight;
  weight.precision(3);
  weight << "holds 1.5 x its weight " << mass_kg * 9.80665 << " N (" << mass_kg << " kg) and its inertia lifted at ";
  bool holds = false;
  for (const std::string& e : watch.snapshot().events) {
    if (e.find(": grasped 'cylinder' at ") == std::string::npos) continue;
    EXPECT_NE(e.find("every finger touches it; friction 1 x 3 fingers x"), std::string::npos) << e;
    EXPECT_NE(e.find(weight.str()), std::string::npos) << e;
    holds = true;
  }
  EXPECT_TRUE(holds) << "no grasp event seen";
}

int main(int argc, char** argv) { return pf_test::runRosTests(argc, argv, "pick_and_place_cell_test", 2); }
