// Calibration: fit the model's effective parameters (by default mu and c) to measured joint angles.
//
// The paper compares the average of joints 2..N with its model and calls the model "tuned"; docs/MODEL.md shows its
// published numbers do not come from its own equations. This is the honest version: a documented objective over
// the measured averages of joints 2..N, a global search (no start point to get wrong), and residuals reported.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/parameters.hpp"

namespace pneumatic_finger {

/// One row of measured angles (layout of data/sierra2022_table1.csv: gauge_pa and joint_1_rad..joint_N_rad).
struct Measurement {
  int line = 0;                    ///< line number in the file, for messages
  double gauge_pa = 0.0;           ///< gauge pressure (Pa)
  std::vector<double> joint_rad;   ///< measured joint angles q_1..q_N (rad)
  double given_average_rad = NAN;  ///< average of joints 2..N read from a column instead (NaN: compute it)

  /// Average of joints 2..N, the quantity the paper (and the fit) compares with the model: the mean of the
  /// measured joints, or the value of the average column when one was named.
  double averageOuterJoints() const;
};

/// Reads measured angles. Lines starting with '#' and blank lines are skipped; the first other line is the header.
/// When @p average_column is not empty, that column gives the joints 2..N average (e.g. the paper's printed
/// paper_avg_rad, which differs from the mean of its printed joints by up to 0.001 rad).
/// @throws ParameterError naming the file and line: missing gauge_pa or joint_k_rad columns (k = 1..N without a
///         gap), a field that is not a finite number, a row with the wrong number of fields, or fewer than
///         @p min_rows rows
std::vector<Measurement> readMeasurementsCsv(const std::string& path, std::size_t min_rows,
                                             const std::string& average_column = "");

/// Same, from text; @p origin names it in messages.
std::vector<Measurement> parseMeasurementsCsv(const std::string& text, const std::string& origin,
                                              std::size_t min_rows, const std::string& average_column = "");

enum class CalibrationObjective {
  kMinimax,       ///< minimise the largest |model - measured| of the joints 2..N averages
  kLeastSquares,  ///< minimise the sum of squared errors of the same averages
};

/// "minimax" or "least_squares". @throws ParameterError for anything else.
CalibrationObjective parseObjective(const std::string& name);
const char* objectiveName(CalibrationObjective objective);

/// The keys that may be fitted (scalar over all chambers), and how each is searched.
bool isFittableKey(const std::string& key);

/// Model against one measurement.
struct Residual {
  double gauge_pa;
  double measured_avg_rad, model_avg_rad;        ///< joints 2..N
  double measured_joint1_rad, model_joint1_rad;  ///< joint 1 (the paper left it out)
  double error_rad() const { return model_avg_rad - measured_avg_rad; }
  double joint1_error_rad() const { return model_joint1_rad - measured_joint1_rad; }
};

struct CalibrationResult {
  FingerParameters parameters;     ///< @p base with the fitted keys replaced
  std::vector<std::string> keys;   ///< fitted keys
  std::vector<double> values;      ///< their fitted values
  double objective_value = 0.0;    ///< max |error| (rad) or sum of squares (rad^2)
  std::vector<Residual> residuals;
  long model_evaluations = 0;
};

/// Residuals of @p parameters against @p data.
std::vector<Residual> residuals(const FingerParameters& parameters, const std::vector<Measurement>& data);

/// Fits @p keys (one or two of isFittableKey) of @p base to @p data.
/// Search: each key over a fixed bracket (mu logarithmically over [1e5, 1e12] Pa; lengths linearly from 0 to
/// the chamber height), a scan followed by golden-section refinement, nested for two keys.
/// @throws ParameterError for an unknown, repeated or non-fittable key, or more than two keys
CalibrationResult calibrate(const FingerParameters& base, const std::vector<std::string>& keys,
                            const std::vector<Measurement>& data, CalibrationObjective objective);

}  // namespace pneumatic_finger
