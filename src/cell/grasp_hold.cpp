#include "pneumatic_finger/cell/grasp_hold.hpp"

#include <cmath>
#include <limits>
#include <sstream>

namespace pneumatic_finger {

GripLimits gripLimits(int finger_count, double most_finger_force_n, double mass_kg, double friction_coefficient,
                      double margin, double lift_acceleration_mps2, double cycle_time_s) {
  GripLimits g;
  g.needed_n = requiredFingerForceN(finger_count, mass_kg, friction_coefficient, margin, lift_acceleration_mps2);
  g.enough = most_finger_force_n >= g.needed_n;  // NaN: not enough
  const double most_friction_n = friction_coefficient * finger_count * most_finger_force_n;
  g.heaviest_part_kg = most_friction_n / (margin * (kStandardGravity + lift_acceleration_mps2));
  // The upward acceleration the grip can bear with this part, a_most; a(T) = a(T0) (T0 / T)^2 gives the cycle.
  const double most_acceleration = most_friction_n / (margin * mass_kg) - kStandardGravity;
  if (!(most_acceleration > 0)) {
    g.shortest_cycle_s = std::numeric_limits<double>::infinity();
  } else {
    g.shortest_cycle_s = cycle_time_s * std::sqrt(std::max(lift_acceleration_mps2, 0.0) / most_acceleration);
  }
  if (g.enough) return g;
  std::ostringstream s;
  s.precision(3);
  s << "the grip cannot hold a " << mass_kg << " kg part at a " << cycle_time_s << " s cycle: each of " << finger_count
    << " fingers must press with " << g.needed_n << " N (" << margin << " x m (g + a) / (friction " << friction_coefficient
    << " x " << finger_count << "), lifted at " << lift_acceleration_mps2 << " m/s^2), and presses with at most "
    << most_finger_force_n << " N at the top of its range. At this cycle, a part of at most " << g.heaviest_part_kg
    << " kg; for this part, ";
  if (std::isinf(g.shortest_cycle_s)) {
    s << "no cycle: even a slow lift needs more grip than the gripper gives";
  } else {
    s << "a cycle of at least " << g.shortest_cycle_s << " s";
  }
  g.message = s.str();
  return g;
}

}  // namespace pneumatic_finger
