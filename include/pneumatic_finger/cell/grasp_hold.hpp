// Whether a grasp holds its object (docs/PICK_AND_PLACE.md, "Does the grasp hold?"): the fingers' normal forces,
// through friction, against the object's weight with a margin. ROS-free.
#pragma once

#include <string>

namespace pneumatic_finger {

/// Standard gravity (m/s^2).
constexpr double kStandardGravity = 9.80665;

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

/// What a gripper whose fingers press with at most @p most_finger_force_n each can lift, by judgeHold's rule: the
/// heaviest part at a lift of @p lift_acceleration_mps2, and the shortest cycle for a part of @p mass_kg. The lift's
/// peak acceleration scales with 1 / cycle time squared (its phase is a fixed share of the cycle, a smoothstep).
struct GripLimits {
  bool enough = false;              ///< the grip the part needs at this cycle is within the gripper's most
  double needed_n = 0.0;            ///< requiredFingerForceN for this part and lift (N)
  double heaviest_part_kg = 0.0;    ///< at this cycle's lift (kg)
  double shortest_cycle_s = 0.0;    ///< for this part (s); infinity: not even a slow lift holds it
  std::string message;              ///< why not, with both figures, when !enough
};
GripLimits gripLimits(int finger_count, double most_finger_force_n, double mass_kg, double friction_coefficient,
                      double margin, double lift_acceleration_mps2, double cycle_time_s);

}  // namespace pneumatic_finger
