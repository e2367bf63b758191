// Where a gripper holds a cylinder so that its fingers close on the side, not on a rim (docs/PICK_AND_PLACE.md, "A
// grasp, not a pinch"): computed from the fingers' mounts and model and the cylinder's size, not typed. ROS-free.
#pragma once

#include <string>
#include <vector>

#include "pneumatic_finger/description/finger_urdf.hpp"

namespace pneumatic_finger {

/// The cylinder's place on the gripper axis (tool z) for a grasp of its side.
struct SideGrasp {
  double centre_depth_m = 0.0;              ///< the cylinder's centre along tool z from the tool frame (m)
  std::vector<double> touch_depth_m;        ///< per finger: where it first meets the side, along tool z (m)
  std::vector<double> touch_pressure_pa;    ///< per finger: at which gauge pressure (Pa)
  double rim_margin_m = 0.0;                ///< the smallest distance of a touch from a rim (m)
};

/// For a cylinder of radius @p radius_m and height @p height_m held on the gripper axis (its own axis along tool z):
/// each finger of @p fingers (mounted on the tool frame) closes on the cylinder's side alone (the cylinder made so
/// tall that no rim is in reach, cut by the finger's plane), and its first touch, taken back to the tool frame, is
/// the depth at which it meets the side. The centre goes at the middle of those depths, so that every touch lies on
/// the side, as far from both rims as the fingers allow.
/// @throws ParameterError naming the finger that does not reach the side within its pressure range, or when the
///         touches span more than the side's height (no depth puts every one on the side)
SideGrasp sideGraspDepth(const std::vector<GripperFinger>& fingers, double radius_m, double height_m);

/// What the twin says of each finger closing on a cylinder of radius @p radius_m and height @p height_m whose centre
/// lies @p centre_depth_m along tool z (its axis along tool z): its first touch (Pa gauge; NaN: none up to its range)
/// and, at @p gauge_pa, its total normal force on the cylinder (N; 0 without contact: totalContactForceN).
struct SideGraspForces {
  std::vector<double> touch_gauge_pa;
  std::vector<double> normal_force_n;
};
SideGraspForces sideGraspForces(const std::vector<GripperFinger>& fingers, double radius_m, double height_m,
                                double centre_depth_m, double gauge_pa);

}  // namespace pneumatic_finger
