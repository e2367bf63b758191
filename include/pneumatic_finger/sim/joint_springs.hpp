// The finger's pressure mechanics as joint springs for a rigid-body engine (docs/MODEL.md, "Joint springs"). ROS-free
// and engine-free: the engine layer (finger_mjcf.hpp) writes them into its own model.
//
// At a gauge pressure P each joint n gets a torsional spring tau_n = -k_n (q_n - q_n0):
//  - its rest angle q_n0 = the twin's free joint angle at P, so the free finger settles to the twin's shape;
//  - its stiffness k_n = M_n(P) / q_n0, M_n the force model's moment at joint n of the finger held straight, so a
//    joint held at q = 0 presses with the twin's moment, and a plate at the tip feels the twin's blocked force;
//  - below the walls' contact (q_n0 = 0, M_n = 0) the elastomer's own bending stiffness, E I / Z, which only holds the
//    straight finger against gravity and inertia.
#pragma once

#include <string>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"

namespace pneumatic_finger {

/// The elastomer modulus the straight finger's bending stiffness takes (Pa): Young's modulus E = 3 mu of a silicone
/// with mu = 100 kPa (Ecoflex and Dragon Skin lie between about 20 and 200 kPa). Stated, not fitted: it only holds the
/// finger before its walls touch.
constexpr double kStraightFingerYoungsModulusPa = 3.0e5;

struct JointSpring {
  double rest_angle_rad = 0.0;          ///< q_n0: the twin's free joint angle (rad)
  double stiffness_nm_per_rad = 0.0;    ///< k_n (N m/rad)
  double pressure_moment_nm = 0.0;      ///< M_n: the moment of the joint held straight (N m), k_n q_n0 in contact
};

/// The elastomer's bending stiffness at joint n (N m/rad): E I / Z_n, I = e L^3 / 12 of the segment's section (width
/// e across, height L away from the bending axis), Z_n the joint's segment length.
double straightBendingStiffnessNmPerRad(const FingerParameters& parameters, int joint);

/// Joint @p joint's (0-based) stiffness (N m/rad) for its rest angle @p rest_angle_rad and its straight joint's moment
/// @p moment_nm: M/q0 in contact, the elastomer's E I/Z before it. The one rule of jointSprings and of the engine's
/// per-step update (pressure_driven_finger.hpp).
double springStiffnessNmPerRad(const FingerParameters& parameters, int joint, double rest_angle_rad, double moment_nm);

/// Joint @p joint's stiffest spring (N m/rad) at the pressures up to @p max_gauge_pa (the range's top; below the
/// limit point under the membrane law), from 64 pressures evenly spread: what sets the shortest period, and so the
/// armature that lets an engine take a long step (finger_mjcf.hpp).
double stiffestSpringNmPerRad(const FingerModel& model, int joint, double max_gauge_pa);

/// The springs of @p model's N joints at @p gauge_pa (joint 1 first). Under the membrane law beyond the limit point
/// (no free shape): empty. @param[out] why the reason when empty
std::vector<JointSpring> jointSprings(const FingerModel& model, double gauge_pa, std::string& why);

}  // namespace pneumatic_finger
