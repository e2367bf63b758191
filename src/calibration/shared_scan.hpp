// A fit and its leave-one-out sharing one scan: the fit's scan of every row is the one each fold takes its starts
// from (calibration.hpp, leaveOneOut), so a law fitted and predicted (calibrateWallLaws) scans once, not twice.
// Internal header of src/calibration.
#pragma once

#include <string>
#include <vector>

#include "pneumatic_finger/calibration/calibration.hpp"
#include "solver.hpp"

namespace pneumatic_finger {

/// calibrate(), keeping its scan in @p record where the fit is one search (not the two steps of every joint with
/// the base face's share, whose record stays empty); nullptr keeps nothing. Without @p uncertainty the result has
/// none (auto's candidates: only the chosen one's is computed, calibrationUncertainty).
CalibrationResult calibrateKeepingScan(const FingerParameters& base, const std::vector<std::string>& keys,
                                       const std::vector<Measurement>& data, CalibrationObjective objective,
                                       CalibrationQuantity quantity, const CalibrationProgress& progress,
                                       ScanRecord* record, bool uncertainty = true);

/// leaveOneOut() from @p record, calibrateKeepingScan's scan of the same base, keys, rows, objective and quantity:
/// the same folds as a scan of its own would start (the scan is deterministic); an empty record is scanned anew.
std::vector<Residual> leaveOneOutFromScan(const FingerParameters& base, const std::vector<std::string>& keys,
                                          const std::vector<Measurement>& data, CalibrationObjective objective,
                                          CalibrationQuantity quantity, const CalibrationProgress& progress,
                                          const std::string& step, ScanRecord record);

/// The same with several rows held out at once: row i is predicted by a fit to the rows of other folds than
/// @p fold_of_row[i] (folds numbered from 0; one row per fold is leave-one-out), its starts from @p record measured
/// without the fold's rows.
std::vector<Residual> heldOutFromScan(const FingerParameters& base, const std::vector<std::string>& keys,
                                      const std::vector<Measurement>& data, CalibrationObjective objective,
                                      CalibrationQuantity quantity, const CalibrationProgress& progress,
                                      const std::string& step, ScanRecord record,
                                      const std::vector<std::size_t>& fold_of_row);

/// @p base under @p law, as each law's fit starts: the paper law's lever b brought within the chamber (b = L/2) where
/// @p base's exceeds it, which @p note then says.
FingerParameters lawStart(const FingerParameters& base, WallLaw law, std::string& note);

}  // namespace pneumatic_finger
