// The cell's grasp rule (core/hold_rule.hpp).
#include "pneumatic_finger/core/hold_rule.hpp"

#include <sstream>

namespace pneumatic_finger {

HoldVerdict judgeHold(int finger_count, double finger_force_n, double mass_kg, double friction_coefficient,
                      double margin, double lift_acceleration_mps2) {
  HoldVerdict v;
  const double normal_n = finger_count * finger_force_n;
  v.friction_n = friction_coefficient * normal_n;
  v.needed_n = margin * mass_kg * (kStandardGravity + lift_acceleration_mps2);
  v.holds = v.friction_n >= v.needed_n;  // NaN holds nothing
  std::ostringstream s;
  s.precision(3);
  s << "friction " << friction_coefficient << " x " << finger_count << " fingers x " << finger_force_n << " N = "
    << v.friction_n << " N " << (v.holds ? "holds" : "is less than") << " " << margin << " x its weight "
    << mass_kg * kStandardGravity << " N (" << mass_kg << " kg)";
  if (lift_acceleration_mps2 != 0.0) {  // the lift's inertia beside the weight
    s << " and its inertia lifted at " << lift_acceleration_mps2 << " m/s^2, m (g + a) = "
      << mass_kg * (kStandardGravity + lift_acceleration_mps2) << " N,";
  }
  s << " = " << v.needed_n << " N";
  v.message = s.str();
  return v;
}

double requiredFingerForceN(int finger_count, double mass_kg, double friction_coefficient, double margin,
                            double lift_acceleration_mps2) {
  return margin * mass_kg * (kStandardGravity + lift_acceleration_mps2) / (friction_coefficient * finger_count);
}

}  // namespace pneumatic_finger
