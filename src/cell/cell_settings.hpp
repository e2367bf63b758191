// cell_sequencer's settings: its parameters' one definition (`cell_sequencer --parameters` prints it for docs/), read
// and checked (cell_sequencer_node.cpp's; an internal header, beside it).
#pragma once

#include <geometry_msgs/Pose.h>
#include <ros/ros.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "pneumatic_finger/cell/cell_schedule.hpp"
#include "pneumatic_finger/cell/side_grasp.hpp"
#include "pneumatic_finger/core/hold_rule.hpp"
#include "pneumatic_finger/ros/parameter_reader.hpp"

namespace pneumatic_finger::sequencer {

namespace pf = pneumatic_finger;

struct Settings {
  std::vector<std::string> joint_names;
  pf::CellWaypoints waypoints;
  double cycle_time_s = 0, grasp_position_rad = 0, grasp_force_n = 0, object_offset_m = 0, object_radius_m = 0,
         object_height_m = 0, publish_rate_hz = 0, object_mass_kg = 0, friction_coefficient = 0, hold_margin = 0;
  double most_finger_force_n = 0;  // the weakest finger's normal force on the object at the top of the fingers' range
  int finger_count = 0;
  int loop_count = 0;
  bool physics = false;  // the object is moved by physics (cell_physics), not carried by the rule
  std::string base_link = "world", tool_link = "tool0", object_id, gripper_file;
};

// The sequencer's parameters: their one definition (`cell_sequencer --parameters` prints it for docs/).
inline const std::vector<pf::NodeParameterSpec>& parameterSpecs() {
  static const std::vector<pf::NodeParameterSpec> table = {
      pf::listParameter("arm_joint_names", "string[]", "-", "the arm's joints", "the arm's joints, in the waypoints' order"),
      pf::listParameter("home", "double[]", "rad", "one per arm joint", "waypoint: where a cycle starts and ends"),
      pf::listParameter("above_pick", "double[]", "rad", "one per arm joint", "waypoint: above the pick table"),
      pf::listParameter("pick", "double[]", "rad", "one per arm joint", "waypoint: the grasp pose"),
      pf::listParameter("above_place", "double[]", "rad", "one per arm joint", "waypoint: above the place table"),
      pf::listParameter("place", "double[]", "rad", "one per arm joint", "waypoint: the release pose"),
      pf::numberParameter("cycle_time_s", 12.0, pf::kMinCycleTimeS, false, pf::kMaxCycleTimeS, "s",
                          "one pick-and-place cycle, as scheduled; where the gripper's fill or release outlasts its "
                          "phase, the cell waits for it (cell/events says how long)"),
      pf::integerParameter("loop_count", 0, 0, 1000000, "cycles to run, then stop the launch (0: forever)"),
      pf::numberParameter("grasp_position_rad", 3.0, 0, true, 20, "rad",
                          "the grasp goal's closing angle: beyond the object, so that the object stops the fingers"),
      pf::numberParameter("grasp_force_n", 0.0, 0, false, 100, "N",
                          "the grasp goal's grip force (max_effort): each finger's total normal force on the object; "
                          "0: the grip this part and this cycle's lift need, hold_margin x m (g + a) / (friction x "
                          "fingers); the cell refuses to start when the gripper cannot give it"),
      pf::textParameter("object_id", "cylinder", "not empty", "the object's name (grasp_object, markers)"),
      pf::textParameter("gripper_file", "", "a gripper file (YAML)",
                        "the gripper's fingers (mounts and actuators): where the object is held is computed from them "
                        "and the object's size, so that the fingers close on its side"),
      pf::numberParameter("object_radius_m", 0.016, 0, true, 1, "m", "the cylinder's radius"),
      pf::numberParameter("object_height_m", 0.035, 0, true, 1, "m", "the cylinder's height"),
      pf::numberParameter("object_mass_kg", 0.01, 0, true, 100, "kg", "the cylinder's mass: what the grip must hold"),
      pf::numberParameter("friction_coefficient", pf::kDefaultFrictionCoefficient, 0, true, 10, "-",
                          "friction between the fingers' silicone and the object (silicone on plastic: about 1)"),
      pf::numberParameter("hold_margin", pf::kDefaultHoldMargin, 1, false, 100, "-",
                          "the grip's friction must hold this many times the object's weight"),
      pf::numberParameter("publish_rate_hz", 50.0, 0, true, 1000, "Hz", "the arm's joint_states and the object's rate"),
      pf::textParameter("physics", "none", "none or mujoco",
                        "who moves the object: none, the sequencer carries it when its rule says the grip holds; "
                        "mujoco, physics does (cell_physics publishes it) and the sequencer only says what its rule "
                        "expects"),
  };
  return table;
}

// The most the weakest finger presses on the held cylinder (N): the twin's normal force at the top of the fingers'
// range (the lowest finger's max_gauge_pa; the force does not fall as the pressure rises).
inline double mostFingerForceN(const std::vector<pf::GripperFinger>& fingers, double radius_m, double height_m,
                               double centre_depth_m) {
  double top_pa = INFINITY;
  for (const pf::GripperFinger& f : fingers) top_pa = std::min(top_pa, f.mount.max_gauge_pa);
  const pf::SideGraspForces at_top = pf::sideGraspForces(fingers, radius_m, height_m, centre_depth_m, top_pa);
  double weakest_n = INFINITY;
  for (double f : at_top.normal_force_n) weakest_n = std::min(weakest_n, f);
  return weakest_n;
}

/// @p refuse_unknown_keys: false where another node reads the cell's file beside its own parameters (cell_physics).
inline Settings readSettings(const ros::NodeHandle& pnh, bool refuse_unknown_keys = true) {
  const pf::NodeParameterReader in(pnh, parameterSpecs());
  Settings s;
  s.joint_names = in.texts("arm_joint_names");
  const std::size_t n = s.joint_names.size();
  s.waypoints = {in.numbers("home", n), in.numbers("above_pick", n), in.numbers("pick", n),
                 in.numbers("above_place", n), in.numbers("place", n)};
  s.cycle_time_s = in.number("cycle_time_s");
  s.loop_count = static_cast<int>(in.number("loop_count"));
  s.grasp_position_rad = in.number("grasp_position_rad");
  s.grasp_force_n = in.number("grasp_force_n");
  s.object_id = in.text("object_id");
  if (s.object_id.empty()) throw pf::ParameterError("parameter 'object_id' must not be empty");
  s.object_radius_m = in.number("object_radius_m");
  s.object_height_m = in.number("object_height_m");
  s.object_mass_kg = in.number("object_mass_kg");
  s.friction_coefficient = in.number("friction_coefficient");
  s.hold_margin = in.number("hold_margin");
  // Where the object is held: computed, so that every finger closes on its side, away from both rims.
  s.gripper_file = in.text("gripper_file");
  if (s.gripper_file.empty()) throw pf::ParameterError("parameter 'gripper_file' must name the gripper's file");
  const std::vector<pf::GripperFinger> fingers = pf::loadGripperFile(s.gripper_file);
  s.finger_count = static_cast<int>(fingers.size());
  const pf::SideGrasp side = pf::sideGraspDepth(fingers, s.object_radius_m, s.object_height_m);
  s.object_offset_m = side.centre_depth_m;
  s.most_finger_force_n = mostFingerForceN(fingers, s.object_radius_m, s.object_height_m, s.object_offset_m);
  ROS_INFO("%s: the object is held with its centre %.1f mm along tool z, where every finger meets its side "
           "(%.1f mm or more from a rim)", ros::this_node::getName().c_str(), 1e3 * side.centre_depth_m, 1e3 * side.rim_margin_m);
  s.publish_rate_hz = in.number("publish_rate_hz");
  const std::string physics = in.text("physics");
  if (physics != "none" && physics != "mujoco") {
    throw pf::ParameterError("parameter 'physics' must be none or mujoco, got '" + physics + "'");
  }
  s.physics = physics == "mujoco";
  if (refuse_unknown_keys) in.refuseUnknownKeys();
  return s;
}

inline void setPose(geometry_msgs::Pose& m, const Eigen::Isometry3d& p) {
  m.position.x = p.translation().x();
  m.position.y = p.translation().y();
  m.position.z = p.translation().z();
  const Eigen::Quaterniond q(p.rotation());
  m.orientation.x = q.x(), m.orientation.y = q.y(), m.orientation.z = q.z(), m.orientation.w = q.w();
}

}  // namespace pneumatic_finger::sequencer
