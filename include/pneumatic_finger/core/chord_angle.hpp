// The chord angle: what one marker on a video gives. A lab that tracks the tip alone, against a fixed point at the
// clamped base, measures the angle from the finger's rest direction to the line from its base to its tip, not the
// tip's own direction (under a uniform bend the tip turns about twice as far). Measured and modelled alike, so that
// a calibration compares like with like.
#pragma once

#include <cmath>

#include "pneumatic_finger/core/units.hpp"

namespace pneumatic_finger {

/// The chord angle (rad) of a tip at (@p tip_x_m, @p tip_y_m) in the finger's frame (the base O_0 at the origin, x
/// along the straight finger, y toward the side it curls to), whose tip direction is @p tip_angle_rad. The line's
/// direction is taken on the turn nearest half the tip angle, so that a finger that curls past a half turn keeps
/// counting (atan2 alone would jump by 2 pi). A finger that turns a full turn brings its tip back to its base, where
/// it meets itself and the line has no direction: past it the chord jumps by pi. NaN for a NaN tip.
inline double chordAngleRad(double tip_x_m, double tip_y_m, double tip_angle_rad) {
  const double line = std::atan2(tip_y_m, tip_x_m);
  if (!std::isfinite(tip_angle_rad)) return line;
  return line + 2.0 * kPi * std::round((0.5 * tip_angle_rad - line) / (2.0 * kPi));
}

}  // namespace pneumatic_finger
