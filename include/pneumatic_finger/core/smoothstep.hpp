// The path every motion of the cell follows, s(u) = 3u^2 - 2u^3 for u = t / T in [0, 1]: at rest at both ends. The
// cell's schedule moves the arm on it, and the physics engine's lift (sim/grasp_lift_trial.hpp) the gripper.
#pragma once

namespace pneumatic_finger {

/// The share of the way covered at @p u (0..1).
inline double smoothstep(double u) { return u * u * (3.0 - 2.0 * u); }

/// Its rate d s/du and its second derivative d^2 s/du^2 at @p u.
inline double smoothstepRate(double u) { return 6.0 * u * (1.0 - u); }
inline double smoothstepCurvature(double u) { return 6.0 * (1.0 - 2.0 * u); }

/// The largest acceleration of a motion of @p distance in @p duration_s on this path: 6 d / T^2, at both ends.
inline double smoothstepPeakAcceleration(double distance, double duration_s) {
  return 6.0 * distance / (duration_s * duration_s);
}

}  // namespace pneumatic_finger
