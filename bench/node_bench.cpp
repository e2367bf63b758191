// node_bench: latency and CPU of finger_node at a given pressure rate, side by side with robot_state_publisher fed
// joint states for the same chain at the same rate (the ecosystem's standard path from joint states to tf).
// Started by bench/node_bench.launch (scripts/bench_node.sh). Prints a Markdown table.
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/JointState.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/units.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pf = pneumatic_finger;

namespace {

struct Series {
  std::vector<double> latency_us;
  long unmatched = 0;
};

std::mutex g_mutex;
std::map<ros::Time, ros::WallTime> g_sent_pressure, g_sent_joints;
Series g_finger_js, g_finger_tf, g_rsp_tf;

void record(Series& s, const std::map<ros::Time, ros::WallTime>& sent, const ros::Time& stamp) {
  const ros::WallTime now = ros::WallTime::now();
  std::lock_guard<std::mutex> lock(g_mutex);
  const auto it = sent.find(stamp);
  if (it == sent.end()) {
    ++s.unmatched;
    return;
  }
  s.latency_us.push_back((now - it->second).toSec() * 1e6);
}

double cpuSeconds(int pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::stringstream s(text.substr(text.rfind(')') + 2));
  std::string field;
  double utime = 0, stime = 0;
  for (int i = 3; i <= 15 && s >> field; ++i) {
    if (i == 14) utime = std::stod(field);
    if (i == 15) stime = std::stod(field);
  }
  return (utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

std::string row(const std::string& name, Series& s, long sent) {
  std::sort(s.latency_us.begin(), s.latency_us.end());
  auto pct = [&s](double q) {
    return s.latency_us.empty() ? 0.0 : s.latency_us[static_cast<std::size_t>(q * (s.latency_us.size() - 1))];
  };
  char b[256];
  std::snprintf(b, sizeof b, "| %s | %ld | %zu | %.0f | %.0f | %.0f |", name.c_str(), sent, s.latency_us.size(), pct(0.5),
                pct(0.99), s.latency_us.empty() ? 0.0 : s.latency_us.back());
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "node_bench");
  ros::NodeHandle nh, pnh("~");
  double rate_hz = 1000, seconds = 10, warmup = 2;
  int finger_pid = 0, rsp_pid = 0;
  std::string config, rsp_prefix = "rsp_", finger_prefix = "bench_";
  pnh.param("rate_hz", rate_hz, rate_hz);
  pnh.param("seconds", seconds, seconds);
  pnh.param("finger_pid", finger_pid, 0);
  pnh.param("rsp_pid", rsp_pid, 0);
  pnh.param("config", config, std::string());
  pf::RawParameterMap raw;
  if (!config.empty()) pf::loadRawParametersFromYamlFile(config, raw);
  pf::FingerModel model(pf::FingerParameters::fromRaw(raw));
  pf::FingerWorkspace ws(model);
  const int n = model.chamberCount();

  ros::Publisher pressure_pub = nh.advertise<sensor_msgs::FluidPressure>("bench/pressure", 2000);
  ros::Publisher joints_pub = nh.advertise<sensor_msgs::JointState>("rsp/joint_states", 2000);
  ros::Subscriber js_sub = nh.subscribe<sensor_msgs::JointState>(
      "bench/joint_states", 2000, [](const sensor_msgs::JointState::ConstPtr& m) {
        record(g_finger_js, g_sent_pressure, m->header.stamp);
      }, ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  const std::string finger_last = finger_prefix + "segment_" + std::to_string(n);
  const std::string rsp_last = rsp_prefix + "segment_" + std::to_string(n);
  ros::Subscriber tf_sub = nh.subscribe<tf2_msgs::TFMessage>(
      "/tf", 4000, [&](const tf2_msgs::TFMessage::ConstPtr& m) {
        for (const auto& t : m->transforms) {
          if (t.child_frame_id == finger_last) record(g_finger_tf, g_sent_pressure, t.header.stamp);
          if (t.child_frame_id == rsp_last) record(g_rsp_tf, g_sent_joints, t.header.stamp);
        }
      }, ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const ros::WallTime wait_until = ros::WallTime::now() + ros::WallDuration(20);
  while ((pressure_pub.getNumSubscribers() == 0 || joints_pub.getNumSubscribers() == 0) && ros::WallTime::now() < wait_until) {
    ros::WallDuration(0.05).sleep();
  }

  sensor_msgs::FluidPressure pressure;
  sensor_msgs::JointState joints;
  for (int i = 1; i <= n; ++i) joints.name.push_back(rsp_prefix + "joint_" + std::to_string(i));
  joints.position.resize(static_cast<std::size_t>(n));
  ros::WallRate rate(rate_hz);
  long sent = 0, k = 0;
  double cpu_finger0 = 0, cpu_rsp0 = 0;
  ros::WallTime t0;
  const ros::WallTime start = ros::WallTime::now();
  bool measuring = false;
  while (ros::ok()) {
    const ros::WallTime now = ros::WallTime::now();
    if (!measuring && (now - start).toSec() >= warmup) {
      std::lock_guard<std::mutex> lock(g_mutex);
      g_finger_js = g_finger_tf = g_rsp_tf = Series();
      g_sent_pressure.clear();  // warm-up messages still in flight must not count
      g_sent_joints.clear();
      cpu_finger0 = finger_pid ? cpuSeconds(finger_pid) : 0;
      cpu_rsp0 = rsp_pid ? cpuSeconds(rsp_pid) : 0;
      t0 = now;
      sent = 0;
      measuring = true;
    }
    if (measuring && (now - t0).toSec() >= seconds) break;
    // A new pressure every message (a slow sine over 0..2 kg/cm^2), so the model's cache never answers.
    const double gauge = pf::kPaPerKgfPerCm2 * (1.0 - std::cos(0.001 * static_cast<double>(k++)));
    const pf::FingerState& s = model.evaluate(gauge, ws);
    const ros::Time stamp = ros::Time::now();
    {
      std::lock_guard<std::mutex> lock(g_mutex);
      g_sent_pressure[stamp] = ros::WallTime::now();
      g_sent_joints[stamp] = g_sent_pressure[stamp];
    }
    pressure.header.stamp = stamp;
    pressure.fluid_pressure = gauge + 101325.0;
    joints.header.stamp = stamp;
    for (int i = 0; i < n; ++i) joints.position[static_cast<std::size_t>(i)] = s.joint_angle_rad[i];
    pressure_pub.publish(pressure);
    joints_pub.publish(joints);
    if (measuring) ++sent;
    rate.sleep();
  }
  ros::WallDuration(0.5).sleep();  // let the last messages arrive
  const double elapsed = (ros::WallTime::now() - t0).toSec();
  std::lock_guard<std::mutex> lock(g_mutex);
  std::cout << "| path | sent | received | p50 (µs) | p99 (µs) | max (µs) |\n|---|---|---|---|---|---|\n"
            << row("finger_node: pressure → joint_states", g_finger_js, sent) << "\n"
            << row("finger_node: pressure → tf", g_finger_tf, sent) << "\n"
            << row("robot_state_publisher: joint_states → tf", g_rsp_tf, sent) << "\n\n";
  char b[256];
  std::snprintf(b, sizeof b,
                "| process | CPU (%% of one core) |\n|---|---|\n| finger_node (model + joint_states + tf + finger_state) | %.1f |\n"
                "| robot_state_publisher (tf only) | %.1f |\n",
                finger_pid ? 100 * (cpuSeconds(finger_pid) - cpu_finger0) / elapsed : -1.0,
                rsp_pid ? 100 * (cpuSeconds(rsp_pid) - cpu_rsp0) / elapsed : -1.0);
  std::cout << b << "\n(" << rate_hz << " Hz for " << seconds << " s after " << warmup << " s of warm-up; unmatched stamps: "
            << g_finger_js.unmatched + g_finger_tf.unmatched + g_rsp_tf.unmatched << ")\n";
  ros::shutdown();
  return 0;
}
