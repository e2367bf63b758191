// Whether a calibration follows its data: the rows its held-out prediction misses beyond what the data's own scatter
// explains, said plainly with what to try (docs/CALIBRATE.md, "When a fit does not follow its data").
#pragma once

#include <string>
#include <vector>

#include "pneumatic_finger/calibration/calibration.hpp"
#include "pneumatic_finger/core/calibration_error.hpp"

namespace pneumatic_finger {

/// A held-out bend is missed when its error exceeds the larger of kFollowFloorRad and kFollowScatters times the data's
/// scatter (bendScatterRad); a held-out pressure, by volume, when its relative error exceeds kFollowPressure.
inline constexpr double kFollowFloorRad = 5.0 * 3.14159265358979323846 / 180.0;
inline constexpr double kFollowScatters = 3.0;
inline constexpr double kFollowPressure = 0.10;

/// The data's own scatter of the bends (rad), from the data alone: the rows set by their pressure, by pressure, each
/// bend's departure from the line through its two neighbours over that departure's spread for independent noise of
/// one standard deviation (sqrt(1 + w^2 + (1 - w)^2), w the row's place between them), 1.4826 times the median (a
/// robust standard deviation, which a snap's few rows do not move). The bend: every joint's sum, the tip angle, the
/// chord. 0 with fewer than kScatterRows such rows: on a few rows far apart the line through two neighbours misses
/// the curve's own bend, which is not noise.
inline constexpr std::size_t kScatterRows = 8;
double bendScatterRad(const std::vector<Measurement>& data);

/// Why the follow bar is what it is, in the report's words: "the larger of 5 deg and 3 times the data's own scatter,
/// S deg", or, where @p scatter_rad is 0, that the scatter needs kScatterRows rows set by their pressure.
std::string followBarReason(double scatter_rad);

/// What the check found: the file's record, and for the report the missed rows and what to try.
struct FitCheck {
  CalibrationError error;
  double bar_rad = 0.0;  ///< the follow bar the held-out bends were held to
  double scatter_rad = 0.0;  ///< the data's own scatter (bendScatterRad)
  std::string warning;  ///< "" where the fit follows its data; else the rows, by how much, and what to try
};

/// Checks a fit's leave-one-out (@p held_out, one per row of @p data; the fit compared @p quantity). @p by_volume:
/// the rows were set by their volume; @p auto_chosen: the keys were chosen by --wall-law auto (else it is suggested).
FitCheck checkFollows(const std::vector<Residual>& held_out, const std::vector<Measurement>& data,
                      CalibrationQuantity quantity, bool by_volume, bool auto_chosen);

}  // namespace pneumatic_finger
