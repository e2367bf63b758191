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

}  // namespace pneumatic_finger
