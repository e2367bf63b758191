// rostest (test/frame_authority.test): either frame authority. With publish_tf the node is the one publisher of its
// finger's frames, and robot_state_publisher, given the node's own URDF and joint states, computes the same
// transforms within 1e-12; without it, robot_state_publisher is the one publisher and the node publishes none.
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <tf2_msgs/TFMessage.h>

#include <cmath>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <tuple>
#include "ros_test_support.hpp"

namespace {

using Key = std::tuple<double, std::string, std::string>;  // stamp, parent, child

struct Recorder {
  std::mutex mutex;
  std::map<std::string, std::set<std::string>> publishers;  // child frame -> caller ids
  std::map<Key, geometry_msgs::Transform> node_tf, shadow_tf;

  void onTf(const ros::MessageEvent<tf2_msgs::TFMessage const>& e, std::map<Key, geometry_msgs::Transform>* store,
            bool record_publisher) {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& t : e.getMessage()->transforms) {
      if (record_publisher) publishers[t.child_frame_id].insert(e.getPublisherName());
      if (store) (*store)[Key(t.header.stamp.toSec(), t.header.frame_id, t.child_frame_id)] = t.transform;
    }
  }
};

double distance(const geometry_msgs::Transform& a, const geometry_msgs::Transform& b) {
  // Translation difference (m) and rotation difference (|q_a - q_b| up to the sign of q), the larger.
  const double dt = std::hypot(std::hypot(a.translation.x - b.translation.x, a.translation.y - b.translation.y),
                               a.translation.z - b.translation.z);
  const double s = a.rotation.x * b.rotation.x + a.rotation.y * b.rotation.y + a.rotation.z * b.rotation.z +
                   a.rotation.w * b.rotation.w < 0 ? -1.0 : 1.0;
  const double dq = std::sqrt(std::pow(a.rotation.x - s * b.rotation.x, 2) + std::pow(a.rotation.y - s * b.rotation.y, 2) +
                              std::pow(a.rotation.z - s * b.rotation.z, 2) + std::pow(a.rotation.w - s * b.rotation.w, 2));
  return std::max(dt, dq);
}

}  // namespace

TEST(FrameAuthority, EitherWayEveryFrameHasOnePublisherAndBothComputeTheSameTransforms) {
  ros::NodeHandle nh;
  Recorder rec;
  auto sub = [&](const std::string& topic, std::map<Key, geometry_msgs::Transform>* store, bool publishers) {
    return nh.subscribe<tf2_msgs::TFMessage>(
        topic, 1000, boost::function<void(const ros::MessageEvent<tf2_msgs::TFMessage const>&)>(
                         [&rec, store, publishers](const ros::MessageEvent<tf2_msgs::TFMessage const>& e) {
                           rec.onTf(e, store, publishers);
                         }));
  };
  ros::Subscriber s1 = sub("/tf", &rec.node_tf, true), s2 = sub("/tf_static", &rec.node_tf, true);
  ros::Subscriber s3 = sub("/a/shadow_tf", &rec.shadow_tf, false), s4 = sub("/a/shadow_tf_static", &rec.shadow_tf, false);
  ros::Publisher pa = nh.advertise<sensor_msgs::FluidPressure>("/a/pressure", 10);
  ros::Publisher pb = nh.advertise<sensor_msgs::FluidPressure>("/b/pressure", 10);
  const ros::WallTime connect_deadline = ros::WallTime::now() + ros::WallDuration(30);
  while ((pa.getNumSubscribers() == 0 || pb.getNumSubscribers() == 0 || s3.getNumPublishers() == 0) &&
         ros::WallTime::now() < connect_deadline) {
    ros::WallDuration(0.05).sleep();
  }
  auto send = [&](double gauge) {
    sensor_msgs::FluidPressure msg;
    msg.header.stamp = ros::Time::now();
    msg.fluid_pressure = gauge + 101325.0;
    pa.publish(msg);
    pb.publish(msg);
  };
  // Warm-up: until both robot_state_publishers have connected to the nodes' joint states and answer (a loaded
  // machine starts them late), then forget what was recorded.
  auto answering = [&rec] {
    std::lock_guard<std::mutex> lock(rec.mutex);
    bool b = false;
    for (const auto& f : rec.publishers) b = b || f.first == "b_segment_7";
    return b && rec.shadow_tf.size() > 8;
  };
  const ros::WallTime warm_deadline = ros::WallTime::now() + ros::WallDuration(30);
  while (!answering() && ros::WallTime::now() < warm_deadline) {
    send(1000.0);
    ros::WallDuration(0.2).sleep();
  }
  ASSERT_TRUE(answering()) << "robot_state_publisher did not answer within 30 s";
  for (double gauge : {0.0, 5e4, 98066.5, 150000.0, 196133.0, 250000.0}) {
    send(gauge);
    ros::WallDuration(0.3).sleep();
  }
  ros::WallDuration(1.0).sleep();
  std::lock_guard<std::mutex> lock(rec.mutex);
  // One publisher per frame; "a" frames from the node, "b" frames from robot_state_publisher.
  int a_frames = 0, b_frames = 0;
  for (const auto& f : rec.publishers) {
    EXPECT_EQ(f.second.size(), 1u) << f.first;
    const std::string who = *f.second.begin();
    if (f.first.rfind("a_", 0) == 0) {
      ++a_frames;
      EXPECT_EQ(who, "/a/finger_node") << f.first;
    } else if (f.first.rfind("b_", 0) == 0) {
      ++b_frames;
      EXPECT_EQ(who, "/b/robot_state_publisher") << f.first;
    }
  }
  EXPECT_EQ(a_frames, 9);  // segment_0..7 and tip
  EXPECT_EQ(b_frames, 9);
  // The node's transforms and robot_state_publisher's, from the node's URDF and joint states, frame by frame.
  int compared = 0;
  for (const auto& t : rec.node_tf) {
    const std::string& child = std::get<2>(t.first);
    if (child.rfind("a_", 0) != 0) continue;
    auto it = rec.shadow_tf.find(t.first);
    if (it == rec.shadow_tf.end() && std::get<0>(t.first) != 0.0) continue;  // a stamp robot_state_publisher skipped
    if (it == rec.shadow_tf.end()) {  // static frames: robot_state_publisher stamps them itself
      for (auto s = rec.shadow_tf.begin(); s != rec.shadow_tf.end(); ++s) {
        if (std::get<1>(s->first) == std::get<1>(t.first) && std::get<2>(s->first) == child) it = s;
      }
    }
    ASSERT_NE(it, rec.shadow_tf.end()) << child;
    EXPECT_LE(distance(t.second, it->second), 1e-12) << std::get<1>(t.first) << " -> " << child;
    ++compared;
  }
  EXPECT_GE(compared, 6 * 7) << "too few transforms compared";
}

int main(int argc, char** argv) { return pf_test::runRosTests(argc, argv, "frame_authority_test", 2); }
