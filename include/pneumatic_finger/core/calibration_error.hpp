// How well a calibration followed its data: the bends it predicted for rows it was not fitted to, recorded in the
// calibrated parameter file (key calibration_error) so that whoever runs the file, finger_node's diagnostics and
// Python's FingerModel, can say so (docs/CALIBRATE.md, "When a fit does not follow its data").
#pragma once

#include <limits>
#include <string>

namespace pneumatic_finger {

struct CalibrationError {
  std::string compared;  ///< what the fit compared (a quantityName); empty: no calibration_error in the file
  double held_out_rms_rad = std::numeric_limits<double>::quiet_NaN();      ///< rms of the held-out bends' errors
  double held_out_largest_rad = std::numeric_limits<double>::quiet_NaN();  ///< the largest of them
  double largest_at_gauge_pa = std::numeric_limits<double>::quiet_NaN();   ///< the row where it is (Pa gauge)
  int missed_rows = 0;      ///< rows missed beyond the follow bar (fit_check.hpp)
  bool follows_data = true;  ///< no row missed beyond it

  bool empty() const { return compared.empty(); }
  /// One line for a person: "held out: 1.81 deg largest (at 45000 Pa), 1.20 deg rms; follows its data", or with
  /// "does NOT follow its data: 12 rows missed".
  std::string describe() const;
};

/// The parameter file's key.
constexpr const char* kCalibrationErrorKey = "calibration_error";

/// The parameter file's calibration_error entry, with a comment that says what it is ("" when @p error is empty).
std::string calibrationErrorToYaml(const CalibrationError& error);

}  // namespace pneumatic_finger
