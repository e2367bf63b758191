// cell_sequencer: drives the pick-and-place cell. It forwards the CellSchedule's answers (the arm's joint states,
// the phase), grasps and releases through the gripper action, and keeps the object: it is carried only when the
// grasp's result says that every finger touches it; a grasp that misses leaves it on its table and says so. The
// object is the grasp_object every finger closes on, a marker, and an interactive marker a person can drag.
// Forward kinematics: KDL on the URDF (arm_kinematics.hpp).
#include <Eigen/Geometry>
#include <actionlib/client/simple_action_client.h>
#include <interactive_markers/interactive_marker_server.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>
#include <std_msgs/String.h>
#include <std_msgs/UInt32.h>
#include <visualization_msgs/MarkerArray.h>

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "pneumatic_finger/GraspObject.h"
#include "pneumatic_finger/GripperCommandAction.h"
#include "pneumatic_finger/cell/cell_schedule.hpp"
#include "pneumatic_finger/cell/grasp_hold.hpp"
#include "pneumatic_finger/cell/side_grasp.hpp"
#include "pneumatic_finger/ros/parameter_reader.hpp"
#include "arm_kinematics.hpp"
#include "cell_settings.hpp"

namespace pf = pneumatic_finger;
using pf::sequencer::parameterSpecs;
using pf::sequencer::readSettings;
using pf::sequencer::Settings;
using pf::sequencer::setPose;

namespace {

// The object: on a table (in the base frame) or held (in the tool frame, fixed there from the grasp on).
struct ObjectState {
  bool held = false;
  Eigen::Isometry3d in_base = Eigen::Isometry3d::Identity();  // while on a table
  Eigen::Isometry3d in_tool = Eigen::Isometry3d::Identity();  // while held
};

// The object (a cylinder) and the two tables as markers, and the object as the fingers' grasp_object.
class Scene {
 public:
  Scene(ros::NodeHandle& nh, const Settings& s, const Eigen::Isometry3d& at_pick, const Eigen::Isometry3d& at_place)
      : settings_(s), at_pick_(at_pick), at_place_(at_place) {
    object_.ns = "object";
    object_.type = visualization_msgs::Marker::CYLINDER;
    object_.scale.x = object_.scale.y = 2 * s.object_radius_m;
    object_.scale.z = s.object_height_m;
    // Translucent: a finger that entered the object would show through it.
    object_.color.r = 0.2f, object_.color.g = 0.5f, object_.color.b = 0.95f, object_.color.a = 0.6f;
    table_ = object_;
    table_.ns = "tables";
    table_.type = visualization_msgs::Marker::CUBE;
    table_.scale.x = table_.scale.y = 0.12;
    table_.scale.z = 0.01;
    table_.color.r = table_.color.g = table_.color.b = 0.55f;
    table_.color.a = 1.0f;
    grasp_object_.id = s.object_id;
    grasp_object_.shape.type = shape_msgs::SolidPrimitive::CYLINDER;
    grasp_object_.shape.dimensions = {s.object_height_m, s.object_radius_m};  // CYLINDER_HEIGHT, CYLINDER_RADIUS
    markers_pub_ = nh.advertise<visualization_msgs::MarkerArray>("cell/markers", 1, true);
    object_pub_ = nh.advertise<pneumatic_finger::GraspObject>("grasp_object", 1, true);
  }

  const Eigen::Isometry3d& pickSpot() const { return at_pick_; }
  void movePickSpot(const Eigen::Isometry3d& spot) { at_pick_ = spot; }

  // The object changed place: the fingers (grasp_object) and rviz (markers) learn it. Under physics, cell_physics
  // publishes where the object is.
  void publishObject(const ObjectState& o, const ros::Time& stamp) {
    if (settings_.physics) return publishMarkers(stamp);
    grasp_object_.header.stamp = stamp;
    grasp_object_.header.frame_id = o.held ? settings_.tool_link : settings_.base_link;
    setPose(grasp_object_.pose, o.held ? o.in_tool : o.in_base);
    object_pub_.publish(grasp_object_);
    publishMarkers(stamp);
  }

  void publishMarkers(const ros::Time& stamp) {
    visualization_msgs::MarkerArray markers;
    object_.header = grasp_object_.header;
    object_.header.stamp = stamp;
    object_.pose = grasp_object_.pose;
    if (!settings_.physics) markers.markers.push_back(object_);
    table_.header.stamp = stamp;
    table_.header.frame_id = settings_.base_link;
    for (int i = 0; i < 2; ++i) {
      table_.id = i;
      Eigen::Isometry3d top = i == 0 ? at_pick_ : at_place_;
      top.translate(Eigen::Vector3d(0, 0, settings_.object_height_m / 2 + 0.005));  // tool z points down
      setPose(table_.pose, Eigen::Isometry3d(Eigen::Translation3d(top.translation())));
      markers.markers.push_back(table_);
    }
    markers_pub_.publish(markers);
  }

 private:
  const Settings& settings_;
  Eigen::Isometry3d at_pick_, at_place_;
  visualization_msgs::Marker object_, table_;
  pneumatic_finger::GraspObject grasp_object_;
  ros::Publisher markers_pub_, object_pub_;
};


// Lets a person drag the object on the pick table in rviz (while it is there): the fingers wrap it where it is.
class ObjectHandle {
 public:
  ObjectHandle(const Settings& s, const Eigen::Isometry3d& spot) : server_("cell_object"), name_(s.object_id) {
    visualization_msgs::InteractiveMarker m;
    m.header.frame_id = s.base_link;
    m.name = s.object_id;
    m.description = "drag the object";
    m.scale = 0.12f;
    setPose(m.pose, Eigen::Isometry3d(Eigen::Translation3d(spot.translation())));
    for (int axis = 0; axis < 3; ++axis) {
      visualization_msgs::InteractiveMarkerControl c;
      c.orientation.w = 1;
      (axis == 0 ? c.orientation.x : axis == 1 ? c.orientation.z : c.orientation.y) = 1;  // x, y, z of the frame
      c.name = std::string("move_") + "xyz"[axis];
      c.interaction_mode = visualization_msgs::InteractiveMarkerControl::MOVE_AXIS;
      c.orientation_mode = visualization_msgs::InteractiveMarkerControl::FIXED;
      m.controls.push_back(c);
    }
    marker_ = m;
    server_.insert(m);
    server_.applyChanges();
  }

  /// The handle is shown only while the object is on the pick table (where dragging moves it), at @p spot.
  void show(bool on, const Eigen::Isometry3d& spot) {
    if (on) {
      setPose(marker_.pose, Eigen::Isometry3d(Eigen::Translation3d(spot.translation())));
      server_.insert(marker_);
      server_.setCallback(name_, callback_);
    } else {
      server_.erase(name_);
    }
    server_.applyChanges();
  }

  template <class Callback>
  void onMove(Callback cb) {
    callback_ = [cb](const visualization_msgs::InteractiveMarkerFeedbackConstPtr& f) {
      if (f->event_type != visualization_msgs::InteractiveMarkerFeedback::POSE_UPDATE) return;
      cb(Eigen::Vector3d(f->pose.position.x, f->pose.position.y, f->pose.position.z));
    };
    server_.setCallback(name_, callback_);
    server_.applyChanges();
  }

 private:
  interactive_markers::InteractiveMarkerServer server_;
  std::string name_;
  visualization_msgs::InteractiveMarker marker_;
  interactive_markers::InteractiveMarkerServer::FeedbackCallback callback_;
};

// The sequencer: each tick, the schedule's arm pose goes out as joint states, and a new phase does its one thing
// (a new object, a grasp, the verdict on the grasp, a release).
class CellSequencer {
 public:
  CellSequencer(ros::NodeHandle& nh, const Settings& settings, const pf::ArmKinematics& arm)
      : settings_(settings),
        arm_(arm),
        schedule_(settings.waypoints, settings.cycle_time_s),
        // The object stands where the gripper will hold it at the pick pose; the place pose puts it on the other table.
        scene_(nh, settings, arm.toolPose(settings.waypoints.pick) * heldOffset(settings),
               arm.toolPose(settings.waypoints.place) * heldOffset(settings)),
        handle_(settings, scene_.pickSpot()),
        gripper_("gripper/gripper_action", true),
        lift_acceleration_mps2_(arm.liftPeakAccelerationMps2(settings.waypoints, schedule_)),
        limits_(pf::gripLimits(settings.finger_count, settings.most_finger_force_n, settings.object_mass_kg,
                               settings.friction_coefficient, settings.hold_margin, lift_acceleration_mps2_,
                               settings.cycle_time_s)),
        grip_n_(settings.grasp_force_n > 0 ? settings.grasp_force_n : limits_.needed_n) {
    object_.in_base = scene_.pickSpot();
    joints_pub_ = nh.advertise<sensor_msgs::JointState>("joint_states", 10);
    phase_pub_ = nh.advertise<std_msgs::String>("cell/phase", 10, true);
    events_pub_ = nh.advertise<std_msgs::String>("cell/events", 10, true);
    cycles_pub_ = nh.advertise<std_msgs::UInt32>("cell/cycles", 10, true);
    js_.name = settings.joint_names;
    handle_.onMove([this](const Eigen::Vector3d& p) { onObjectDragged(p); });
    scene_.publishObject(object_, ros::Time::now());
  }

  /// Waits for the gripper action server; false (with the reason logged) when it does not come.
  bool waitForGripper(ros::NodeHandle& nh) {
    if (gripper_.waitForServer(ros::Duration(30.0))) return true;
    ROS_FATAL("cell_sequencer: no gripper action server at '%s'", nh.resolveName("gripper/gripper_action").c_str());
    return false;
  }

  /// Whether the gripper can give the grip it will be asked for; false (with the reason logged) when the part at
  /// this cycle needs more than the gripper's most (grasp_force_n 0), or a grasp_force_n is set above that most.
  bool checkGrip() const {
    if (settings_.grasp_force_n <= 0 && !limits_.enough) {
      ROS_FATAL("cell_sequencer: %s", limits_.message.c_str());
      return false;
    }
    if (!(grip_n_ <= settings_.most_finger_force_n)) {
      ROS_FATAL("cell_sequencer: grasp_force_n %g N is more than the weakest finger gives, %.3g N at the top of its "
                "range", grip_n_, settings_.most_finger_force_n);
      return false;
    }
    if (grip_n_ < limits_.needed_n) {
      ROS_WARN("cell_sequencer: grasp_force_n %g N is less than this part and lift need, %.3g N per finger: its "
               "grasps will slip", grip_n_, limits_.needed_n);
    }
    ROS_INFO("cell_sequencer: each finger grips with %.3g N (the part and the lift need %.3g N; the gripper gives up "
             "to %.3g N)", grip_n_, limits_.needed_n, settings_.most_finger_force_n);
    return true;
  }

  /// Runs the cycles until ROS stops or loop_count cycles are done.
  void run() {
    ros::Rate rate(settings_.publish_rate_hz);
    start_ = ros::Time::now();
    ROS_INFO("cell_sequencer: %.1f s cycles, %s; object '%s' at (%.3f, %.3f, %.3f) m", settings_.cycle_time_s,
             settings_.loop_count ? (std::to_string(settings_.loop_count) + " loops").c_str() : "looping",
             settings_.object_id.c_str(), object_.in_base.translation().x(), object_.in_base.translation().y(),
             object_.in_base.translation().z());
    while (ros::ok() && tick()) rate.sleep();
  }

 private:
  static Eigen::Isometry3d heldOffset(const Settings& s) {
    return Eigen::Isometry3d(Eigen::Translation3d(0, 0, s.object_offset_m));
  }

  // The schedule's clock: the time since the start, less what the cell has waited for the gripper. Leaving the grasp
  // (inflate) or the place (deflate) while the gripper action still works would lift an object the fingers have not
  // closed on, or pull the fingers out of one they still hold: the clock stops at the phase's end instead, until the
  // action is done (it ends itself when its fill does not settle), and cell/events says how long the cell waited.
  double scheduleTime(const ros::Time& now) {
    const double wanted = (now - start_).toSec() - waited_s_;
    const pf::CellStep next = schedule_.at(wanted);
    const bool gripper_phase = last_phase_ == pf::CellPhase::kGrasp || last_phase_ == pf::CellPhase::kPlace;
    const bool waiting = wait_started_s_ >= 0;
    if (!first_ && gripper_phase && (waiting || next.phase != last_phase_) && gripperBusy()) {
      if (wait_started_s_ < 0) wait_started_s_ = (now - start_).toSec();
      waited_s_ = (now - start_).toSec() - schedule_time_s_;
      return schedule_time_s_;
    }
    if (wait_started_s_ >= 0) {
      say("cycle " + std::to_string(next.cycle + (next.phase == pf::CellPhase::kApproach ? 0 : 1)) + ": " +
          pf::cellPhaseName(last_phase_) + ": the cell waited " +
          std::to_string((now - start_).toSec() - wait_started_s_) + " s beyond the schedule for the gripper (" +
          gripper_.getState().toString() + ")");
      wait_started_s_ = -1.0;
    }
    schedule_time_s_ = wanted;
    return wanted;
  }

  bool gripperBusy() const {
    const auto state = gripper_.getState();
    return state == actionlib::SimpleClientGoalState::PENDING || state == actionlib::SimpleClientGoalState::ACTIVE;
  }

  // One tick of the schedule; false when the last cycle is done.
  bool tick() {
    const pf::CellStep step = schedule_.at(scheduleTime(ros::Time::now()));
    if (step.cycle != last_cycle_ && !countCycle(step.cycle)) return false;
    js_.header.stamp = ros::Time::now();
    js_.position = step.arm;
    joints_pub_.publish(js_);
    // The drag handle changes outside the object's lock: the marker server calls back under its own lock.
    int show_handle = -1;
    if (first_ || step.phase != last_phase_) show_handle = enterPhase(step, arm_.toolPose(step.arm));
    if (show_handle >= 0) handle_.show(show_handle == 1, scene_.pickSpot());
    if (ticks_++ % 5 == 0) scene_.publishMarkers(js_.header.stamp);
    return true;
  }

  // A cycle completed: counted on cell/cycles; false when it was the last.
  bool countCycle(long cycle) {
    std_msgs::UInt32 cycles;
    cycles.data = static_cast<unsigned>(cycle);
    cycles_pub_.publish(cycles);
    ROS_INFO("cell_sequencer: cycle %ld complete", cycle);
    last_cycle_ = cycle;
    if (settings_.loop_count > 0 && cycle >= settings_.loop_count) {
      ROS_INFO("cell_sequencer: %d cycles done", settings_.loop_count);
      return false;
    }
    return true;
  }

  // What a new phase does. Returns 1 to show the drag handle, 0 to hide it, -1 to leave it.
  int enterPhase(const pf::CellStep& step, const Eigen::Isometry3d& tool) {
    std_msgs::String msg;
    msg.data = pf::cellPhaseName(step.phase);
    phase_pub_.publish(msg);
    ROS_INFO("cell_sequencer: cycle %ld: %s", step.cycle + 1, msg.data.c_str());
    std::lock_guard<std::mutex> lock(object_mutex_);
    int show_handle = -1;
    if (step.phase == pf::CellPhase::kApproach && !first_) {
      object_ = ObjectState();  // a new object on the pick table for the next cycle
      object_.in_base = scene_.pickSpot();
      scene_.publishObject(object_, js_.header.stamp);
      show_handle = 1;
    } else if (step.phase == pf::CellPhase::kGrasp) {
      pf::GripperCommandGoal goal;
      goal.position = settings_.grasp_position_rad;
      goal.max_effort = grip_n_;
      gripper_.sendGoal(goal);
    } else if (step.phase == pf::CellPhase::kLift) {
      if (judgeGrasp(step.cycle + 1, tool)) show_handle = 0;
    } else if (step.phase == pf::CellPhase::kPlace) {
      release(tool);
    }
    last_phase_ = step.phase;
    first_ = false;
    return show_handle;
  }

  // At the lift: the object is carried only when the twin says every finger touches it. true: it is carried.
  bool judgeGrasp(long cycle, const Eigen::Isometry3d& tool) {
    const auto state = gripper_.getState();
    const auto result = gripper_.getResult();
    // Every finger touches: the grip holds the object only if its friction holds the weight (each finger presses
    // with at least the result's grip force, the smallest).
    const pf::HoldVerdict hold =
        result ? pf::judgeHold(settings_.finger_count, result->effort, settings_.object_mass_kg,
                               settings_.friction_coefficient, settings_.hold_margin, lift_acceleration_mps2_)
               : pf::HoldVerdict{};
    if (settings_.physics) {  // physics carries it or not (cell_physics says which); the rule's verdict beside it
      say("cycle " + std::to_string(cycle) + ": the static rule expects the grip to " +
          (hold.holds ? "carry '" : "lose '") + settings_.object_id + "': " + hold.message);
      return false;
    }
    if (state == actionlib::SimpleClientGoalState::SUCCEEDED && result && result->stalled && !hold.holds) {
      say("cycle " + std::to_string(cycle) + ": grasp slips, '" + settings_.object_id + "' stays on the pick table: " +
          "every finger touches it, but " + hold.message);
      return false;
    }
    if (state == actionlib::SimpleClientGoalState::SUCCEEDED && result && result->stalled) {
      object_.held = true;
      object_.in_tool = tool.inverse() * object_.in_base;
      scene_.publishObject(object_, js_.header.stamp);
      say("cycle " + std::to_string(cycle) + ": grasped '" + settings_.object_id + "' at " +
          pf::formatMessage(result->gauge_pa) + " Pa: every finger touches it; " + hold.message);
      return true;
    }
    say("cycle " + std::to_string(cycle) + ": grasp missed, '" + settings_.object_id + "' stays on the pick table: " +
        (state == actionlib::SimpleClientGoalState::SUCCEEDED
             ? std::string("not every finger touches it")
             : "the gripper action " + state.toString() + (state.getText().empty() ? "" : ": " + state.getText())));
    return false;
  }

  // At the place: the gripper opens, and a carried object stays where it is, in the base frame.
  void release(const Eigen::Isometry3d& tool) {
    gripper_.sendGoal(pf::GripperCommandGoal());  // position 0: open
    if (!object_.held) return;
    object_.held = false;
    object_.in_base = tool * object_.in_tool;
    scene_.publishObject(object_, js_.header.stamp);
  }

  // A person dragged the object on the pick table (rviz): the fingers wrap it where it now is.
  void onObjectDragged(const Eigen::Vector3d& p) {
    std::lock_guard<std::mutex> lock(object_mutex_);
    Eigen::Isometry3d spot = scene_.pickSpot();
    spot.translation() = p;
    scene_.movePickSpot(spot);
    if (object_.held) return;
    object_.in_base = spot;
    scene_.publishObject(object_, ros::Time::now());
  }

  void say(const std::string& text) {
    std_msgs::String msg;
    msg.data = text;
    events_pub_.publish(msg);
    ROS_INFO("cell_sequencer: %s", text.c_str());
  }

  const Settings& settings_;
  const pf::ArmKinematics& arm_;
  pf::CellSchedule schedule_;
  Scene scene_;
  ObjectHandle handle_;
  actionlib::SimpleActionClient<pf::GripperCommandAction> gripper_;
  double lift_acceleration_mps2_;  // the lift's peak upward acceleration (m/s^2)
  pf::GripLimits limits_;          // what this part at this lift needs, against the gripper's most
  double grip_n_;                  // the grip each finger is asked for (N): grasp_force_n, or what the part needs
  ros::Publisher joints_pub_, phase_pub_, events_pub_, cycles_pub_;
  sensor_msgs::JointState js_;
  std::mutex object_mutex_;  // the object is moved by the ticks and by the drag handle's callback
  ObjectState object_;
  ros::Time start_;
  bool first_ = true;
  pf::CellPhase last_phase_ = pf::CellPhase::kApproach;
  double waited_s_ = 0.0;         // the schedule's clock is this far behind the wall clock: waits for the gripper
  double schedule_time_s_ = 0.0;  // the schedule time of the last tick
  double wait_started_s_ = -1.0;  // when the current wait began (since the start); -1: not waiting
  long last_cycle_ = 0;
  int ticks_ = 0;
};

}  // namespace

// The last cycle is done: the launch ends as Ctrl-C ends it (roslaunch stops every node and exits 0), instead of
// roslaunch finding its required sequencer gone and saying "REQUIRED process has died", which reads as a failure.
// Only when roslaunch started this process; the sequencer then waits to be stopped with the others.
void endLaunch() {
  const pid_t parent = getppid();
  std::ifstream cmdline("/proc/" + std::to_string(parent) + "/cmdline");
  const std::string command((std::istreambuf_iterator<char>(cmdline)), std::istreambuf_iterator<char>());
  if (command.find("roslaunch") == std::string::npos) return;
  ROS_INFO("cell_sequencer: the run is complete; stopping the cell");
  if (kill(parent, SIGINT) == 0) ros::waitForShutdown();
}

int main(int argc, char** argv) {
  // Line by line even into a pipe or a file, so that the nodes' lines of one cell interleave in time order.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  if (pf::printParametersIfAsked(argc, argv, parameterSpecs())) return 0;
  ros::init(argc, argv, "cell_sequencer");
  ros::NodeHandle nh, pnh("~");
  Settings settings;
  std::unique_ptr<pf::ArmKinematics> arm;
  try {
    settings = readSettings(pnh);
    pf::CellSchedule check(settings.waypoints, settings.cycle_time_s);  // refuses a schedule it cannot run
    std::string xml;
    if (!nh.getParam("robot_description", xml)) throw std::runtime_error("no arm URDF in 'robot_description'");
    arm = std::make_unique<pf::ArmKinematics>(xml, settings.base_link, settings.tool_link, settings.joint_names);
  } catch (const std::exception& e) {
    ROS_FATAL("cell_sequencer: %s", e.what());
    return 2;
  }
  ros::AsyncSpinner spinner(1);  // the action client's and the interactive marker's callbacks
  spinner.start();
  CellSequencer sequencer(nh, settings, *arm);
  if (!sequencer.checkGrip() || !sequencer.waitForGripper(nh)) return 2;
  sequencer.run();
  if (ros::ok()) endLaunch();
  return 0;
}
