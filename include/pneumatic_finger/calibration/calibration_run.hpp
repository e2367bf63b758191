// One calibration as finger_calibrate and Python's pf.calibrate run it: the same defaults (what to compare, which
// keys, which wall laws), the same data check, the same leave-one-out and error bar, so that the two interfaces
// cannot answer one data set differently.
#pragma once

#include <chrono>
#include <ostream>
#include <string>
#include <vector>

#include "pneumatic_finger/calibration/calibration.hpp"
#include "pneumatic_finger/calibration/model_selection.hpp"
#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/pressure_range.hpp"
#include "pneumatic_finger/core/calibration_error.hpp"
#include "pneumatic_finger/core/tip_uncertainty.hpp"

namespace pneumatic_finger {

/// What to fit; every field empty takes the tool's default.
struct CalibrationRequest {
  std::string wall_law;        ///< "auto", "paper" or "membrane"; empty: the parameters' wall_law
  std::vector<std::string> keys;  ///< fittable keys, any number; empty: each law's defaultFitKeys
  std::string objective = "minimax";
  std::string compare;         ///< a quantityName; empty: average with an average column, else defaultQuantity
  std::string average_column;  ///< the column that gives the joints 2..N average (e.g. paper_avg_rad), or empty
  std::string drive;           ///< what set each row: "pressure" (gauge_pa) or "volume" (supplied_volume_m3); empty:
                               ///< pressure where the data has gauge_pa, else volume
  bool leave_one_out = true;   ///< predict each row by a fit to the others (always, when laws are compared)
  CalibrationProgress progress;  ///< hears each step of a long run (CalibrationProgressPrinter); empty: nobody
};

/// Prints a calibration's progress for a person waiting on it: nothing for the first @p quiet_s seconds (a short
/// calibration says nothing), then one line per step at most every @p quiet_s seconds, "WHO: 12.4 s: thick law:
/// leave-one-out, row 5 of 15", to @p out (the tools' and Python's stderr).
class CalibrationProgressPrinter {
 public:
  CalibrationProgressPrinter(std::ostream& out, std::string who, double quiet_s = 2.0);
  void operator()(const std::string& step);

 private:
  std::ostream* out_;
  std::string who_;
  double quiet_s_;
  std::chrono::steady_clock::time_point start_, last_;
};

/// A calibration's answer: each law's fit (one unless wall_law is "auto"), the chosen one, and what the data said.
struct CalibrationRun {
  CalibrationQuantity quantity = CalibrationQuantity::kEveryJoint;
  CalibrationObjective objective = CalibrationObjective::kMinimax;
  bool by_volume = false;  ///< the rows were set by their supplied volume (CalibrationRequest::drive)
  std::vector<WallLawFit> fits;
  std::size_t chosen = 0;
  /// --wall-law auto with no keys named: every candidate it tried (selectModel), and the chosen one's place among
  /// them. Empty otherwise.
  std::vector<CandidateFit> candidates;
  std::size_t chosen_candidate = 0;
  /// The error bar (tipUncertainty of the chosen fit and its leave-one-out); empty without leave-one-out.
  TipUncertainty tip_uncertainty;
  /// The factor the bar's leave-one-out errors were widened by: auto's chosen score corrected for the choice, over
  /// its own (selectionOptimism); 1 where nothing was chosen among candidates.
  double leave_one_out_widening = 1.0;
  /// Every warning, the data's first (columns not read), then the fit's (keys that trade off, keys on a bound), and
  /// last, where the fit does not follow its data, which rows it misses and what to try (checkFollows).
  std::vector<std::string> warnings;
  /// How well the chosen fit followed its data, held out (checkFollows); empty without leave-one-out. follow_bar_rad
  /// and scatter_rad: the bar each held-out bend was held to, and the data's own scatter it came from.
  CalibrationError calibration_error;
  double follow_bar_rad = 0.0, scatter_rad = 0.0;

  const WallLawFit& best() const { return fits.at(chosen); }
};

/// The base parameters of a calibration from the file's raw keys: where @p wall_law asks for the membrane law (or
/// "auto"), the keys are validated under it whatever law the file names (each law's fit sets its own), so that a wall the membrane law allows
/// (wall_critical_height_m above chamber_height_m) is not refused before the law is chosen.
/// @throws ParameterError as FingerParameters::fromRaw
FingerParameters calibrationBase(RawParameterMap raw, const std::string& wall_law);

/// Runs @p request on @p data from @p base. @throws ParameterError naming what was wrong (calibrate,
/// checkMeasurementsPlausible, an unknown objective, quantity or law)
CalibrationRun runCalibration(const FingerParameters& base, const MeasurementSet& data,
                              const CalibrationRequest& request);

/// The range a calibration validated: @p file_range (the base file's) with validated_max_gauge_pa the highest pressure
/// of the fit's rows (measured, or the model's at a row's volume), and max_gauge_pa raised to it where it was lower.
PressureRange calibratedRange(const CalibrationRun& run, const PressureRange& file_range);

/// The calibrated parameter file's keys: the chosen fit's parameters, the calibrated range and the error bar, each in
/// the one YAML writer's numbers (formatYamlNumber), so that rosparam, yaml-cpp and PyYAML read the same values.
/// finger_calibrate --output and Python's calibrate(output=) write it.
std::string calibratedParameterYaml(const CalibrationRun& run, const PressureRange& file_range);

}  // namespace pneumatic_finger
