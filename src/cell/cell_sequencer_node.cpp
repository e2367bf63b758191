// cell_sequencer: drives the pick-and-place cell. It forwards the CellSchedule's answers: the arm's joint states,
// the regulator's setpoint, the phase, and the object and tables as markers. Forward kinematics: KDL on the URDF.
#include <Eigen/Geometry>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/tree.hpp>
#include <kdl_parser/kdl_parser.hpp>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>
#include <std_msgs/String.h>
#include <std_msgs/UInt32.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "pneumatic_finger/cell/cell_schedule.hpp"

namespace pf = pneumatic_finger;

namespace {

struct Settings {
  std::vector<std::string> joint_names;
  pf::CellWaypoints waypoints;
  double cycle_time_s = 12.0, grasp_gauge_pa = 147099.75, object_offset_m = 0.075, object_radius_m = 0.016,
         object_height_m = 0.035, publish_rate_hz = 50.0;
  int loop_count = 0;
  std::string base_link = "world", tool_link = "tool0";
};

pf::ArmJoints readJoints(const ros::NodeHandle& pnh, const std::string& key, std::size_t n) {
  pf::ArmJoints v;
  if (!pnh.getParam(key, v) || v.size() != n) {
    throw std::runtime_error("parameter '" + key + "' must be a list of " + std::to_string(n) + " joint values (rad)");
  }
  return v;
}

Settings readSettings(const ros::NodeHandle& pnh) {
  Settings s;
  if (!pnh.getParam("arm_joint_names", s.joint_names) || s.joint_names.empty()) {
    throw std::runtime_error("parameter 'arm_joint_names' is missing");
  }
  const std::size_t n = s.joint_names.size();
  s.waypoints = {readJoints(pnh, "home", n), readJoints(pnh, "above_pick", n), readJoints(pnh, "pick", n),
                 readJoints(pnh, "above_place", n), readJoints(pnh, "place", n)};
  pnh.param("cycle_time_s", s.cycle_time_s, s.cycle_time_s);
  pnh.param("loop_count", s.loop_count, s.loop_count);
  pnh.param("grasp_gauge_pa", s.grasp_gauge_pa, s.grasp_gauge_pa);
  pnh.param("object_offset_m", s.object_offset_m, s.object_offset_m);
  pnh.param("object_radius_m", s.object_radius_m, s.object_radius_m);
  pnh.param("object_height_m", s.object_height_m, s.object_height_m);
  pnh.param("publish_rate_hz", s.publish_rate_hz, s.publish_rate_hz);
  if (s.loop_count < 0) throw std::runtime_error("parameter 'loop_count' must be >= 0 (0: forever)");
  if (!(s.grasp_gauge_pa > 0 && s.grasp_gauge_pa <= 1e6)) {
    throw std::runtime_error("parameter 'grasp_gauge_pa' must be in (0, 1e6]");
  }
  if (!(s.publish_rate_hz > 0 && s.publish_rate_hz <= 1000)) {
    throw std::runtime_error("parameter 'publish_rate_hz' must be in (0, 1000]");
  }
  return s;
}

// The arm's forward kinematics base -> tool, from the URDF, with KDL.
class ArmKinematics {
 public:
  ArmKinematics(const std::string& urdf_xml, const std::string& base, const std::string& tool,
                const std::vector<std::string>& joint_names) {
    KDL::Tree tree;
    if (!kdl_parser::treeFromString(urdf_xml, tree)) throw std::runtime_error("'robot_description' does not parse");
    if (!tree.getChain(base, tool, chain_)) {
      throw std::runtime_error("'robot_description' has no chain from '" + base + "' to '" + tool + "'");
    }
    for (const auto& segment : chain_.segments) {
      if (segment.getJoint().getType() == KDL::Joint::None) continue;
      const auto it = std::find(joint_names.begin(), joint_names.end(), segment.getJoint().getName());
      if (it == joint_names.end()) {
        throw std::runtime_error("joint '" + segment.getJoint().getName() + "' of the arm is not in 'arm_joint_names'");
      }
      index_.push_back(static_cast<std::size_t>(it - joint_names.begin()));
    }
  }

  Eigen::Isometry3d toolPose(const pf::ArmJoints& q) const {
    KDL::JntArray joints(static_cast<unsigned>(index_.size()));
    for (std::size_t i = 0; i < index_.size(); ++i) joints(static_cast<unsigned>(i)) = q[index_[i]];
    KDL::Frame frame;
    KDL::ChainFkSolverPos_recursive(chain_).JntToCart(joints, frame);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    double x, y, z, w;
    frame.M.GetQuaternion(x, y, z, w);
    pose.linear() = Eigen::Quaterniond(w, x, y, z).toRotationMatrix();
    pose.translation() = Eigen::Vector3d(frame.p.x(), frame.p.y(), frame.p.z());
    return pose;
  }

 private:
  KDL::Chain chain_;
  std::vector<std::size_t> index_;  // chain joint -> position in arm_joint_names
};

void setPose(visualization_msgs::Marker& m, const Eigen::Isometry3d& p) {
  m.pose.position.x = p.translation().x();
  m.pose.position.y = p.translation().y();
  m.pose.position.z = p.translation().z();
  const Eigen::Quaterniond q(p.rotation());
  m.pose.orientation.x = q.x(), m.pose.orientation.y = q.y(), m.pose.orientation.z = q.z(), m.pose.orientation.w = q.w();
}

// The object (a cylinder, in tool0 while held, else on its table) and the two tables, as markers.
class SceneMarkers {
 public:
  SceneMarkers(const Settings& s, const Eigen::Isometry3d& at_pick, const Eigen::Isometry3d& at_place)
      : held_(Eigen::Translation3d(0, 0, s.object_offset_m)), at_pick_(at_pick), at_place_(at_place),
        tool_link_(s.tool_link), base_link_(s.base_link), height_m_(s.object_height_m) {
    object_.ns = "object";
    object_.type = visualization_msgs::Marker::CYLINDER;
    object_.scale.x = object_.scale.y = 2 * s.object_radius_m;
    object_.scale.z = s.object_height_m;
    object_.color.r = 0.2f, object_.color.g = 0.5f, object_.color.b = 0.95f, object_.color.a = 1.0f;
    table_ = object_;
    table_.ns = "tables";
    table_.type = visualization_msgs::Marker::CUBE;
    table_.scale.x = table_.scale.y = 0.12;
    table_.scale.z = 0.01;
    table_.color.r = table_.color.g = table_.color.b = 0.55f;
  }

  visualization_msgs::MarkerArray at(pf::ObjectPlace place, const ros::Time& stamp) {
    visualization_msgs::MarkerArray markers;
    object_.header.stamp = stamp;
    if (place == pf::ObjectPlace::kHeld) {
      object_.header.frame_id = tool_link_;
      setPose(object_, held_);
    } else {
      object_.header.frame_id = base_link_;
      setPose(object_, place == pf::ObjectPlace::kOnPlaceTable ? at_place_ : at_pick_);
    }
    markers.markers.push_back(object_);
    table_.header.stamp = stamp;
    table_.header.frame_id = base_link_;
    for (int i = 0; i < 2; ++i) {
      table_.id = i;
      Eigen::Isometry3d top = i == 0 ? at_pick_ : at_place_;
      top.translate(Eigen::Vector3d(0, 0, height_m_ / 2 + 0.005));  // tool z points down: +z is below the object
      setPose(table_, Eigen::Isometry3d(Eigen::Translation3d(top.translation())));
      markers.markers.push_back(table_);
    }
    return markers;
  }

 private:
  visualization_msgs::Marker object_, table_;
  Eigen::Isometry3d held_, at_pick_, at_place_;
  std::string tool_link_, base_link_;
  double height_m_;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "cell_sequencer");
  ros::NodeHandle nh, pnh("~");
  Settings settings;
  std::unique_ptr<pf::CellSchedule> schedule;
  std::unique_ptr<ArmKinematics> arm;
  try {
    settings = readSettings(pnh);
    schedule = std::make_unique<pf::CellSchedule>(settings.waypoints, settings.cycle_time_s, settings.grasp_gauge_pa);
    std::string xml;
    if (!nh.getParam("robot_description", xml)) throw std::runtime_error("no arm URDF in 'robot_description'");
    arm = std::make_unique<ArmKinematics>(xml, settings.base_link, settings.tool_link, settings.joint_names);
  } catch (const std::exception& e) {
    ROS_FATAL("cell_sequencer: %s", e.what());
    return 2;
  }
  // The object stands where the gripper will hold it at the pick pose, and is left where the place pose puts it.
  const Eigen::Isometry3d held(Eigen::Translation3d(0, 0, settings.object_offset_m));
  const Eigen::Isometry3d at_pick = arm->toolPose(settings.waypoints.pick) * held;
  const Eigen::Isometry3d at_place = arm->toolPose(settings.waypoints.place) * held;
  SceneMarkers scene(settings, at_pick, at_place);

  ros::Publisher joints_pub = nh.advertise<sensor_msgs::JointState>("joint_states", 10);
  ros::Publisher setpoint_pub = nh.advertise<std_msgs::Float64>("gripper/setpoint", 10);
  ros::Publisher marker_pub = nh.advertise<visualization_msgs::MarkerArray>("cell/markers", 1, true);
  ros::Publisher phase_pub = nh.advertise<std_msgs::String>("cell/phase", 10, true);
  ros::Publisher cycles_pub = nh.advertise<std_msgs::UInt32>("cell/cycles", 10, true);

  sensor_msgs::JointState js;
  js.name = settings.joint_names;
  std_msgs::Float64 setpoint;
  ros::Rate rate(settings.publish_rate_hz);
  const ros::Time start = ros::Time::now();
  bool first = true;
  pf::CellPhase last_phase = pf::CellPhase::kApproach;
  long last_cycle = 0;
  int tick = 0;
  ROS_INFO("cell_sequencer: %.1f s cycles, %s; object at (%.3f, %.3f, %.3f) m", settings.cycle_time_s,
           settings.loop_count ? (std::to_string(settings.loop_count) + " loops").c_str() : "looping",
           at_pick.translation().x(), at_pick.translation().y(), at_pick.translation().z());
  while (ros::ok()) {
    const pf::CellStep step = schedule->at((ros::Time::now() - start).toSec());
    if (step.cycle != last_cycle) {
      std_msgs::UInt32 cycles;
      cycles.data = static_cast<unsigned>(step.cycle);
      cycles_pub.publish(cycles);
      ROS_INFO("cell_sequencer: cycle %ld complete", step.cycle);
      last_cycle = step.cycle;
      if (settings.loop_count > 0 && step.cycle >= settings.loop_count) {
        ROS_INFO("cell_sequencer: %d cycles done", settings.loop_count);
        break;
      }
    }
    js.header.stamp = ros::Time::now();
    js.position = step.arm;
    joints_pub.publish(js);
    setpoint.data = step.setpoint_gauge_pa;
    setpoint_pub.publish(setpoint);
    if (first || step.phase != last_phase) {
      std_msgs::String msg;
      msg.data = pf::cellPhaseName(step.phase);
      phase_pub.publish(msg);
      ROS_INFO("cell_sequencer: cycle %ld: %s (gripper setpoint %.0f Pa gauge)", step.cycle + 1, msg.data.c_str(),
               step.setpoint_gauge_pa);
      last_phase = step.phase;
      first = false;
    }
    if (tick++ % 5 == 0) marker_pub.publish(scene.at(step.object, js.header.stamp));
    rate.sleep();
  }
  return 0;
}
