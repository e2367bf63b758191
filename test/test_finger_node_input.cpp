// rostest (test/finger_node_input.test): the input rules of the running node, where they meet ROS.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/JointState.h>

#include <cmath>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "pneumatic_finger/FingerModelState.h"
#include "ros_test_support.hpp"

namespace {

using pf_test::kAtm;

struct Finger {
  std::string ns, hardware_id;
  ros::Publisher pressure;
  ros::Subscriber joints, states;
  std::vector<sensor_msgs::JointState> joint_states;
  std::vector<pneumatic_finger::FingerModelState> finger_states;
};

std::mutex g_mutex;
std::map<std::string, diagnostic_msgs::DiagnosticStatus> g_latest;  // hardware id -> newest "pressure input" status
long g_reports = 0;

void onDiagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
  std::lock_guard<std::mutex> lock(g_mutex);
  for (const auto& s : m->status) {
    if (s.name.find("pressure input") != std::string::npos) {
      g_latest[s.hardware_id] = s;
      ++g_reports;
    }
  }
}

std::string value(const diagnostic_msgs::DiagnosticStatus& s, const std::string& key) {
  for (const auto& kv : s.values) {
    if (kv.key == key) return kv.value;
  }
  return "";
}

class FingerNodeInput : public testing::Test {
 protected:
  static void connect(Finger& f, ros::NodeHandle& nh) {
    f.pressure = nh.advertise<sensor_msgs::FluidPressure>(f.ns + "/pressure", 100);
    f.joints = nh.subscribe<sensor_msgs::JointState>(f.ns + "/joint_states", 100, [&f](const sensor_msgs::JointState::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(g_mutex);
      f.joint_states.push_back(*m);
    });
    f.states = nh.subscribe<pneumatic_finger::FingerModelState>(
        f.ns + "/finger_state", 100, [&f](const pneumatic_finger::FingerModelState::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(g_mutex);
          f.finger_states.push_back(*m);
        });
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30);
    while ((f.pressure.getNumSubscribers() == 0 || f.joints.getNumPublishers() == 0 || f.states.getNumPublishers() == 0) &&
           ros::WallTime::now() < deadline) {
      ros::WallDuration(0.02).sleep();
    }
  }
  static void send(Finger& f, double gauge_pa, ros::Time stamp) {
    sensor_msgs::FluidPressure msg;
    msg.header.stamp = stamp;
    msg.fluid_pressure = gauge_pa + kAtm;
    f.pressure.publish(msg);
  }
  static std::size_t published(Finger& f) {
    std::lock_guard<std::mutex> lock(g_mutex);
    return f.joint_states.size();
  }
};

}  // namespace

TEST_F(FingerNodeInput, SteadyUnstampedInputLeavesDiagnosticsOk) {
  ros::NodeHandle nh;
  ros::Subscriber diag = nh.subscribe("/diagnostics", 100, onDiagnostics);
  Finger f{"/steady", "steady_pneumatic_finger", {}, {}, {}, {}, {}};
  connect(f, nh);
  // `rostopic pub -r 20 /pressure sensor_msgs/FluidPressure "{fluid_pressure: ...}"`: no stamp, for 3.5 s.
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(3.5);
  while (ros::WallTime::now() < end) {
    send(f, 98066.5, ros::Time(0));
    ros::WallDuration(0.05).sleep();
  }
  ASSERT_GT(published(f), 40u);
  {
    std::lock_guard<std::mutex> lock(g_mutex);
    for (const auto& js : f.joint_states) EXPECT_FALSE(js.header.stamp.isZero());  // the receive time, never 0
    ASSERT_TRUE(g_latest.count(f.hardware_id)) << "no diagnostics from the steady finger";
    const auto& s = g_latest[f.hardware_id];
    EXPECT_EQ(s.level, diagnostic_msgs::DiagnosticStatus::OK) << s.message;
    EXPECT_GT(std::stol(value(s, "zero stamps (receive time used)")), 40) << "zero stamps are counted";
  }
}

TEST_F(FingerNodeInput, ASolverWithNoAnswerPublishesNothingAndSaysWhy) {
  ros::NodeHandle nh;
  ros::Subscriber diag = nh.subscribe("/diagnostics", 100, onDiagnostics);
  Finger f{"/paper", "paper_pneumatic_finger", {}, {}, {}, {}, {}};
  connect(f, nh);
  send(f, 1000.0, ros::Time::now());  // the paper's closed forms answer here
  ros::WallDuration(0.5).sleep();
  ASSERT_EQ(published(f), 1u);
  send(f, 100.0, ros::Time::now());  // and find no root here (c = 0): nothing may be published
  ros::WallDuration(0.5).sleep();
  EXPECT_EQ(published(f), 1u) << "a solver failure was published";
  // Diagnostics: WARN naming the solver, the failure counted; the published state stayed finite.
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(5);
  diagnostic_msgs::DiagnosticStatus s;
  while (ros::WallTime::now() < deadline) {
    {
      std::lock_guard<std::mutex> lock(g_mutex);
      if (g_latest.count(f.hardware_id) && value(g_latest[f.hardware_id], "solver failures (last state kept)") == "1") {
        s = g_latest[f.hardware_id];
        break;
      }
    }
    ros::WallDuration(0.05).sleep();
  }
  EXPECT_EQ(s.level, diagnostic_msgs::DiagnosticStatus::WARN) << s.message;
  EXPECT_NE(s.message.find("solver 'paper' found no finite answer"), std::string::npos) << s.message;
  std::lock_guard<std::mutex> lock(g_mutex);
  for (const auto& js : f.joint_states) {
    for (double q : js.position) EXPECT_TRUE(std::isfinite(q));
  }
  for (const auto& st : f.finger_states) {
    for (double x : st.stretch) EXPECT_TRUE(std::isfinite(x));
    for (double x : st.half_angle_rad) EXPECT_TRUE(std::isfinite(x));
  }
}

int main(int argc, char** argv) { return pf_test::runRosTests(argc, argv, "finger_node_input_test", 2); }
