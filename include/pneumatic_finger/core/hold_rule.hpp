// The cell's grasp rule (docs/PICK_AND_PLACE.md, "Does the grasp hold?"): the fingers' normal forces, through
// friction, against the object's weight with a margin. Its one definition, used by the cell (cell/grasp_hold.hpp) and
// by the design search's grip target (core/side_grip.hpp). ROS-free.
#pragma once

#include <string>

namespace pneumatic_finger {

/// Standard gravity (m/s^2).
constexpr double kStandardGravity = 9.80665;

/// The rule's defaults, the cell's (cell_sequencer's friction_coefficient and hold_margin): silicone on plastic grips
/// with a friction coefficient of about 1, and the friction must hold one and a half times the load.
constexpr double kDefaultFrictionCoefficient = 1.0;
constexpr double kDefaultHoldMargin = 1.5;

struct HoldVerdict {
  bool holds = false;
  double friction_n = 0.0;  ///< the most friction the grip can give: friction coefficient x the total normal force (N)
  double needed_n = 0.0;    ///< what it must: margin x the object's weight (N)
  std::string message;      ///< the numbers, in words, for cell/events
};

/// The grip of @p finger_count fingers, each pressing with at least @p finger_force_n (N), holds an object of
/// @p mass_kg lifted against gravity at @p lift_acceleration_mps2 (upward; 0: a slow lift) when
/// @p friction_coefficient x the total normal force >= @p margin x m (g + a). Friction only: the fingers close on the
/// side of the object, not under it.
HoldVerdict judgeHold(int finger_count, double finger_force_n, double mass_kg, double friction_coefficient,
                      double margin, double lift_acceleration_mps2 = 0.0);

/// The grip each of @p finger_count fingers must press with (N) for judgeHold to hold: judgeHold's rule solved for
/// the finger force, margin x m (g + a) / (friction coefficient x finger_count). What the cell asks the gripper for.
double requiredFingerForceN(int finger_count, double mass_kg, double friction_coefficient, double margin,
                            double lift_acceleration_mps2 = 0.0);

}  // namespace pneumatic_finger
