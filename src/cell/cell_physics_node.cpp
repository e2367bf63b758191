// cell_physics: the pick-and-place cell as physics (CellPhysics, docs/SIMULATION.md), for
// `pick_and_place_cell.launch physics:=mujoco`. It steps MuJoCo on the ROS clock (real or /clock): the arm follows
// the sequencer's joint_states through its position actuators, every finger's springs follow the regulator's
// pressure, and the part is a free body. Where physics puts the part goes out as grasp_object (the twins close on
// it) and on tf; the simulated arm's and fingers' joints on physics/joint_states; what physics did at each lift on
// cell/events.
#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/String.h>
#include <std_msgs/UInt32.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "pneumatic_finger/GraspObject.h"
#include "pneumatic_finger/ros/node_main.hpp"
#include "pneumatic_finger/cell/side_grasp.hpp"
#include "pneumatic_finger/ros/parameter_reader.hpp"
#include "pneumatic_finger/sim/cell_physics.hpp"
#include "cell_settings.hpp"

namespace pf = pneumatic_finger;

namespace {

// The node's own parameters; the cell's (the part, the arm's joints and pick pose) are config/cell.yaml's, loaded
// beside them as the sequencer loads them.
const std::vector<pf::NodeParameterSpec>& physicsParameterSpecs() {
  static const std::vector<pf::NodeParameterSpec> table = {
      pf::textParameter("arm_urdf_file", "", "a URDF file", "the arm without its gripper (urdf/industrial_arm.urdf)"),
      pf::numberParameter("step_rate_hz", 200.0, 1, false, 2000, "Hz",
                          "how often the engine catches up with the clock (each time in steps of the file's 1 ms)"),
      pf::numberParameter("publish_rate_hz", 50.0, 1, false, 1000, "Hz",
                          "the part's grasp_object and tf, and the simulated fingers' joint states"),
  };
  return table;
}

class CellPhysicsNode {
 public:
  CellPhysicsNode(ros::NodeHandle& nh, ros::NodeHandle& pnh)
      : settings_(pf::sequencer::readSettings(pnh, false)) {
    const pf::NodeParameterReader in(pnh, physicsParameterSpecs());
    const std::vector<pf::GripperFinger> fingers = pf::loadGripperFile(settings_.gripper_file);
    pf::GraspScene scene;
    scene.object_radius_m = settings_.object_radius_m;
    scene.object_height_m = settings_.object_height_m;
    scene.object_mass_kg = settings_.object_mass_kg;
    scene.object_centre_depth_m = settings_.object_offset_m;
    physics_ = std::make_unique<pf::CellPhysics>(pf::readRobotUrdfFile(in.text("arm_urdf_file")), fingers,
                                                 settings_.joint_names, settings_.waypoints.pick, scene,
                                                 pf::MjcfOptions(), settings_.waypoints.place);
    atmospheric_pa_ = fingers.front().parameters.atmospheric_pressure_pa;
    part_rest_z_ = physics_->partPose().translation().z();
    object_.id = settings_.object_id;
    object_.shape.type = shape_msgs::SolidPrimitive::CYLINDER;
    object_.shape.dimensions = {settings_.object_height_m, settings_.object_radius_m};
    object_.header.frame_id = settings_.base_link;
    object_pub_ = nh.advertise<pneumatic_finger::GraspObject>("grasp_object", 1, true);
    // The part as the sequencer draws it (translucent blue, namespace "object" of cell/markers), where physics has it.
    marker_.ns = "object";
    marker_.type = visualization_msgs::Marker::CYLINDER;
    marker_.scale.x = marker_.scale.y = 2 * settings_.object_radius_m;
    marker_.scale.z = settings_.object_height_m;
    marker_.color.r = 0.2f, marker_.color.g = 0.5f, marker_.color.b = 0.95f, marker_.color.a = 0.6f;
    markers_pub_ = nh.advertise<visualization_msgs::MarkerArray>("cell/markers", 1);
    joints_pub_ = nh.advertise<sensor_msgs::JointState>("physics/joint_states", 10);
    events_pub_ = nh.advertise<std_msgs::String>("cell/events", 10, true);
    subs_.push_back(nh.subscribe("joint_states", 50, &CellPhysicsNode::onJointStates, this));
    subs_.push_back(nh.subscribe("gripper/pressure", 10, &CellPhysicsNode::onPressure, this));
    subs_.push_back(nh.subscribe("cell/phase", 10, &CellPhysicsNode::onPhase, this));
    subs_.push_back(nh.subscribe("cell/cycles", 10, &CellPhysicsNode::onCycles, this));
    step_timer_ = nh.createTimer(ros::Duration(1.0 / in.number("step_rate_hz")), &CellPhysicsNode::onStep, this);
    publish_timer_ = nh.createTimer(ros::Duration(1.0 / in.number("publish_rate_hz")), &CellPhysicsNode::onPublish,
                                    this);
    // The simulated robot's frames (physics/..., robot_state_publisher under that prefix) hang from world as the
    // twin's do.
    geometry_msgs::TransformStamped root;
    root.header.stamp = ros::Time::now();
    root.header.frame_id = settings_.base_link;
    root.child_frame_id = "physics/" + settings_.base_link;
    root.transform.rotation.w = 1.0;
    static_tf_.sendTransform(root);
    ROS_INFO("cell_physics: MuJoCo steps the cell (%d bodies, a %g ms step); the part is %g kg", physics_->model().nbody,
             1e3 * physics_->model().opt.timestep, settings_.object_mass_kg);
  }

 private:
  // The sequencer's arm joints (the fingers' joint states, on the same topic, are the twins': not targets).
  void onJointStates(const sensor_msgs::JointState::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<double> target(settings_.joint_names.size());
    std::size_t found = 0;
    for (std::size_t i = 0; i < msg->name.size() && i < msg->position.size(); ++i) {
      const auto it = std::find(settings_.joint_names.begin(), settings_.joint_names.end(), msg->name[i]);
      if (it == settings_.joint_names.end()) continue;
      target[static_cast<std::size_t>(it - settings_.joint_names.begin())] = msg->position[i];
      ++found;
    }
    if (found != target.size()) return;
    // The first pose puts the arm there (the cell starts at home, the scene at the pick pose); then it follows.
    const ros::Time now = ros::Time::now();
    if (!arm_placed_) {
      physics_->placeArm(target);
      target_from_ = target_to_ = filtered_ = target;
      filtered_rate_.assign(target.size(), 0.0);
      arm_placed_ = true;
    } else {
      target_from_ = targetAt(now);
      target_to_ = target;
      target_period_s_ = std::clamp((now - target_t0_).toSec(), 1e-3, 0.1);
    }
    target_t0_ = now;
  }

  // The sequencer's poses come at its publish rate (50 Hz): the engine's targets move from one to the next over the
  // period between them, so that the arm's servos are not jolted at every message (a step in the target is a spike
  // of acceleration that shakes a held part loose).
  // (Written into a member: the engine asks at every step, 1 kHz, and a heap vector each time is waste.)
  const std::vector<double>& targetAt(const ros::Time& t) {
    const double u = std::clamp((t - target_t0_).toSec() / target_period_s_, 0.0, 1.0);
    interpolated_.resize(target_to_.size());
    for (std::size_t j = 0; j < interpolated_.size(); ++j) {
      interpolated_[j] = target_from_[j] + u * (target_to_[j] - target_from_[j]);
    }
    return interpolated_;
  }

  // And they pass a critically damped second-order filter (kTargetFilterHz): the corners of the piecewise-linear path
  // become bounded accelerations, as a real arm's trajectory controller makes them.
  const std::vector<double>& filteredTarget(const std::vector<double>& target, double dt) {
    const double w = 2.0 * M_PI * kTargetFilterHz;
    if (filtered_.size() != target.size()) filtered_ = target, filtered_rate_.assign(target.size(), 0.0);
    for (std::size_t j = 0; j < target.size(); ++j) {
      filtered_rate_[j] += dt * (w * w * (target[j] - filtered_[j]) - 2.0 * w * filtered_rate_[j]);
      filtered_[j] += dt * filtered_rate_[j];
    }
    return filtered_;
  }
  static constexpr double kTargetFilterHz = 5.0;

  void onPressure(const sensor_msgs::FluidPressure::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (std::isfinite(msg->fluid_pressure)) gauge_pa_ = msg->fluid_pressure - atmospheric_pa_;
  }

  void onPhase(const std_msgs::String::ConstPtr& msg);
  void onCycles(const std_msgs::UInt32::ConstPtr& msg);
  void onStep(const ros::TimerEvent&);
  void onPublish(const ros::TimerEvent&);
  void say(const std::string& what) {
    std_msgs::String m;
    m.data = what;
    events_pub_.publish(m);
    ROS_INFO("cell_physics: %s", what.c_str());
  }

  pf::sequencer::Settings settings_;
  std::unique_ptr<pf::CellPhysics> physics_;
  std::mutex mutex_;  // the engine, between the timers' and the subscribers' callbacks
  double atmospheric_pa_ = 0.0, gauge_pa_ = 0.0, part_rest_z_ = 0.0;
  long cycles_ = 0;  // completed, as cell/cycles says
  bool arm_placed_ = false;
  std::vector<double> target_from_, target_to_;  // the arm's targets move from one pose to the next
  std::vector<double> interpolated_;              // targetAt's answer
  ros::Time target_t0_;
  double target_period_s_ = 0.02;
  std::vector<double> filtered_, filtered_rate_;  // the targets after the filter, and their rates
  ros::Time last_step_;
  pneumatic_finger::GraspObject object_;
  visualization_msgs::Marker marker_;
  ros::Publisher markers_pub_, object_pub_, joints_pub_, events_pub_;
  std::vector<ros::Subscriber> subs_;
  ros::Timer step_timer_, publish_timer_;
  tf2_ros::TransformBroadcaster tf_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
};

// At the end of the move (the descent to the place table begins) the part is in the grip or not: it is where the
// gripper holds a part (its centre object_offset_m along tool z from tool0), or elsewhere.
void CellPhysicsNode::onPhase(const std_msgs::String::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  const bool lift = msg->data == pf::cellPhaseName(pf::CellPhase::kLift);
  if (!lift && msg->data != pf::cellPhaseName(pf::CellPhase::kDescendToPlace)) return;
  const Eigen::Isometry3d tool = physics_->toolPose();
  const Eigen::Vector3d held = tool * Eigen::Vector3d(0.0, 0.0, settings_.object_offset_m);
  const double off_m = (physics_->partPose().translation() - held).norm();
  char b[240];
  if (lift) {
    const std::vector<int> contacts = physics_->fingerContacts();
    const long touching = std::count_if(contacts.begin(), contacts.end(), [](int n) { return n > 0; });
    std::snprintf(b, sizeof b, "cycle %ld: physics: the lift starts with %ld of %zu fingers on '%s', %.1f mm from "
                  "where the grip holds it", cycles_ + 1, touching, contacts.size(), settings_.object_id.c_str(),
                  1e3 * off_m);
  } else if (off_m < 0.5 * settings_.object_height_m) {
    std::snprintf(b, sizeof b, "cycle %ld: physics: the grip carried '%s' (%.1f mm from where it was grasped in the "
                  "grip)", cycles_ + 1, settings_.object_id.c_str(), 1e3 * off_m);
  } else {
    std::snprintf(b, sizeof b, "cycle %ld: physics: '%s' slipped out of the grip (%.0f mm from the grip, %.1f mm above "
                  "the pick table)", cycles_ + 1, settings_.object_id.c_str(), 1e3 * off_m,
                  1e3 * (physics_->partPose().translation().z() - part_rest_z_));
  }
  say(b);
}

// A completed cycle: the next one picks a new part from the pick table.
void CellPhysicsNode::onCycles(const std_msgs::UInt32::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (static_cast<long>(msg->data) == cycles_) return;
  cycles_ = msg->data;
  physics_->resetPart();
}

// The engine catches up with the clock in its own steps, at most 0.1 s per call (a stalled process does not make it
// run for long).
void CellPhysicsNode::onStep(const ros::TimerEvent&) {
  std::lock_guard<std::mutex> lock(mutex_);
  const ros::Time now = ros::Time::now();
  if (last_step_.isZero() || now < last_step_) last_step_ = now;
  const double dt = physics_->model().opt.timestep;
  const int steps = std::min(100, static_cast<int>((now - last_step_).toSec() / dt));
  std::string why;
  if (steps == 100) ROS_WARN_THROTTLE(10.0, "cell_physics: the engine falls behind the clock (0.1 s in one call)");
  for (int i = 0; i < steps && arm_placed_; ++i) {
    physics_->setArmTargets(filteredTarget(targetAt(last_step_ + ros::Duration((i + 1) * dt)), dt));
    if (!physics_->step(gauge_pa_, why)) {
      ROS_WARN_THROTTLE(5.0, "cell_physics: %s", why.c_str());
      break;
    }
  }
  last_step_ = steps == 100 ? now : last_step_ + ros::Duration(steps * dt);
}

void CellPhysicsNode::onPublish(const ros::TimerEvent&) {
  std::lock_guard<std::mutex> lock(mutex_);
  const ros::Time now = ros::Time::now();
  const Eigen::Isometry3d part = physics_->partPose();
  object_.header.stamp = now;
  pf::sequencer::setPose(object_.pose, part);
  object_pub_.publish(object_);
  visualization_msgs::MarkerArray markers;
  marker_.header = object_.header;
  marker_.pose = object_.pose;
  markers.markers.push_back(marker_);
  markers_pub_.publish(markers);
  geometry_msgs::TransformStamped t;
  t.header = object_.header;
  t.child_frame_id = settings_.object_id;
  t.transform.translation.x = object_.pose.position.x;
  t.transform.translation.y = object_.pose.position.y;
  t.transform.translation.z = object_.pose.position.z;
  t.transform.rotation = object_.pose.orientation;
  tf_.sendTransform(t);
  sensor_msgs::JointState js;
  js.header.stamp = now;
  physics_->jointStates(js.name, js.position);
  joints_pub_.publish(js);
}

}  // namespace

int main(int argc, char** argv) {
  return pf::runNode<CellPhysicsNode>(argc, argv, "cell_physics", physicsParameterSpecs(), 2);
}
