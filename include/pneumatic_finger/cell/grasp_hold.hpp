// What a gripper can lift at a cycle (docs/PICK_AND_PLACE.md, "Does the grasp hold?"), by the grasp rule of
// core/hold_rule.hpp. ROS-free.
#pragma once

#include <string>

#include "pneumatic_finger/core/hold_rule.hpp"

namespace pneumatic_finger {

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
