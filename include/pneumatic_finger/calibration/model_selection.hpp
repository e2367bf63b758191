// What --wall-law auto chooses, and how: the wall law, the keys and the comparison, each candidate judged on one
// yardstick a user reads, the bend held out at its measured pressure (docs/CALIBRATE.md, "What auto chooses").
#pragma once

#include <string>
#include <vector>

#include "pneumatic_finger/calibration/calibration.hpp"

namespace pneumatic_finger {

/// The yardstick over held-out rows: the bend error (rad; every joint where the row measured its joints, else the
/// tip angle, else the chord, base to tip, which a tip position gives too) and, for rows set by their volume with their pressure
/// measured, the pressure's relative error (model/measured - 1; 1 rad of bend weighs as the whole pressure, as
/// tip_angle+gauge_pa weighs them), and the blocked force where a row measured it, as a share of the data's largest
/// measured force (the whole range weighing as 1 rad). A row the model gives no shape counts as kUnshapedBendRad of bend error: a
/// comparison that avoids the snap cannot win by losing the snap's rows.
struct HeldOutError {
  double bend_rad = 0.0;  ///< root mean square of the bends' errors (rad)
  double pressure = 0.0;  ///< root mean square of the pressures' relative errors (0 where none is compared)
  double force = 0.0;     ///< the largest blocked force's error held out, as a share of the largest measured force
  double score = 0.0;     ///< sqrt(bend_rad^2 + pressure^2): what the candidates are ranked by
  double standard_error = 0.0;  ///< of score, from the rows' spread (for the report)
  std::vector<double> row_squared;  ///< each held-out row's squared error, in the rows' order (NaN: none measured)
  int unshaped = 0;       ///< rows with a measured bend that the model gave no shape
};
inline constexpr double kUnshapedBendRad = 1.5707963267948966;  // a quarter turn

/// A held-out row's bend errors (rad): every joint's where the row measured its joints, else the tip angle's, else
/// the chord's (which a tip position gives too); NaN where the model gave no shape; empty where no bend was measured.
std::vector<double> heldOutBendErrors(const Residual& r);

/// The yardstick of @p held_out (rows predicted without themselves); @p by_volume: the rows were set by their volume.
HeldOutError heldOutError(const std::vector<Residual>& held_out, bool by_volume);

/// The least share of the score a candidate must take off to be clearly better (clearlyBetter).
inline constexpr double kNegligibleGain = 0.01;

/// Whether @p candidate predicts the same rows clearly better than @p current: its score is lower by more than
/// kNegligibleGain of current's, and the mean of the rows' gains in squared error (current's minus candidate's, row
/// by row) exceeds its own standard error (a paired test, the one-standard-error rule of cross-validation: the
/// held-out rows' own scatter is the bar a gain must clear).
bool clearlyBetter(const HeldOutError& candidate, const HeldOutError& current);

/// One candidate auto tried: a law, a comparison and keys, with its cross-validated yardstick and its time.
struct CandidateFit {
  WallLaw law = WallLaw::kPaper;
  CalibrationQuantity quantity = CalibrationQuantity::kTipAngle;
  std::vector<std::string> keys;
  HeldOutError held_out;  ///< cross-validated (kCrossValidationFolds interleaved folds; each row alone where fewer)
  double seconds = 0.0;   ///< its fit and its folds (wall clock)
  std::string skipped;    ///< why it has no fit (the data cannot identify its keys, ...); empty: fitted
  bool selected = false;  ///< the set its law and comparison's selection stopped at
};

/// The choice's optimism: the chosen candidate's held-out score is the best of several, and so too low. Tibshirani &
/// Tibshirani's rule (Ann. Appl. Stat. 3, 2009) estimates by how much, from the folds the candidates already share:
/// per fold, the chosen's mean squared error there less the least any candidate makes there; the folds' mean. The
/// corrected score is sqrt(score^2 + that). Each fold compares the candidates on the rows the chosen one is scored on;
/// skipped candidates take no part. 0 for one candidate.
double selectionOptimism(const std::vector<CandidateFit>& tried, std::size_t chosen);

/// The chosen candidate's score corrected for the choice: sqrt(score^2 + selectionOptimism).
double correctedScore(const std::vector<CandidateFit>& tried, std::size_t chosen);

/// Folds of the selection's cross-validation: rows i with the same i mod kCrossValidationFolds are held out together
/// (interleaved, so that every fold spans the pressures, the snap's included); data with at most that many rows hold
/// each row out alone (leave-one-out).
inline constexpr std::size_t kCrossValidationFolds = 8;

/// What auto chose, and everything it tried, in the order tried.
struct ModelSelection {
  std::vector<CandidateFit> tried;
  WallLawFit chosen;  ///< the best selected candidate: its fit, its leave-one-out and its note
  std::size_t chosen_index = 0;  ///< its place in tried
};

/// --wall-law auto with no keys named. For each law of @p laws and each comparison of @p comparisons, forward
/// selection: start from defaultFitKeys; try each further key the law can use (J_m and kappa for the membrane and
/// thick walls; the gas and the skin's share by volume with measured pressures), one at a time; keep the one that
/// lowers the cross-validated yardstick most, if it is clearlyBetter; stop when none is. A candidate that cannot be
/// fitted (too few rows for its keys, no row with a shape anywhere) is skipped with its reason. Of the selected
/// candidates, in the order tried, a later one is chosen over the one chosen so far only where it is clearlyBetter;
/// the chosen one is predicted by leave-one-out for the report and the error bar.
/// @throws ParameterError when no candidate could be fitted, with each one's reason
ModelSelection selectModel(const FingerParameters& base, const std::vector<WallLaw>& laws,
                           const std::vector<CalibrationQuantity>& comparisons, const std::vector<Measurement>& data,
                           CalibrationObjective objective, bool by_volume, const CalibrationProgress& progress = {});

/// The candidates as the report prints them, one per line after a header, each line starting "# ": law, comparison,
/// keys, the held-out bend (deg) and pressure (%), rows without a shape, seconds, and "selected" / "<- chosen", or
/// the reason it was skipped.
std::string candidatesTable(const std::vector<CandidateFit>& tried, std::size_t chosen);

}  // namespace pneumatic_finger
