#include "pneumatic_finger/calibration/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <mutex>
#include <sstream>

#include "every_core.hpp"
#include "fit_problem.hpp"
#include "fit_space.hpp"
#include "shared_scan.hpp"
#include "solver.hpp"

namespace pneumatic_finger {

CalibrationObjective parseObjective(const std::string& name) {
  if (name == "minimax") return CalibrationObjective::kMinimax;
  if (name == "least_squares") return CalibrationObjective::kLeastSquares;
  if (name == "huber") return CalibrationObjective::kHuber;
  throw ParameterError("unknown objective '" + name + "'; known: minimax, least_squares, huber");
}

const char* objectiveName(CalibrationObjective objective) {
  return objective == CalibrationObjective::kMinimax ? "minimax"
         : objective == CalibrationObjective::kHuber ? "huber"
                                                     : "least_squares";
}


bool isFittableKey(const std::string& key) {
  if (key.rfind(kDrawingPrefix, 0) == 0) {
    const std::string name = key.substr(std::string(kDrawingPrefix).size());
    return std::find(std::begin(kFittableDrawn), std::end(kFittableDrawn), name) != std::end(kFittableDrawn);
  }
  return std::find(std::begin(kFittable), std::end(kFittable), key) != std::end(kFittable);
}


namespace {

// The objective over @p rows (reduce: the largest |term|, the sum of squares or of Huber's losses), the terms being
// what @p quantity compares in each row.
double objectiveOver(const std::vector<Residual>& rows, CalibrationQuantity quantity, CalibrationObjective objective) {
  std::vector<double> all;
  for (const Residual& r : rows) {
    for (double e : r.terms(quantity)) {
      if (std::isnan(e)) return std::numeric_limits<double>::infinity();  // a row the model gives no shape for
      all.push_back(e);
    }
  }
  const Eigen::Map<const Eigen::VectorXd> terms(all.data(), static_cast<Eigen::Index>(all.size()));
  // Huber's scale from these terms themselves: the objective of a set of rows, as a fit's is of its own.
  return reduce(terms, objective, objective == CalibrationObjective::kHuber ? huberScale(terms) : 0.0);
}

}  // namespace

namespace {

// What the drive needs: the pressure against the volume and the dead gas are seen only when the rows are set by
// their volume (under pressure the model's pressure is the measured, and the gas takes no part in the shape).
void checkTheDrive(const FingerParameters& base, const std::vector<std::string>& keys,
                   const std::vector<Measurement>& data, CalibrationQuantity quantity) {
  const bool by_volume = std::any_of(data.begin(), data.end(), [](const Measurement& m) { return m.driven_by_volume; });
  const bool pressure = quantity == CalibrationQuantity::kGauge || quantity == CalibrationQuantity::kTipAngleAndGauge;
  if (!by_volume && pressure) {
    throw ParameterError(std::string("'") + quantityName(quantity) + "' compares the model's pressure at each row's "
                         "supplied volume with the measured one: drive the rows by volume (--drive volume, "
                         "drive=\"volume\")");
  }
  for (const char* volume_only : {"dead_volume_m3", "chamber_growth_ratio"}) {
    if (!by_volume && std::count(keys.begin(), keys.end(), volume_only) > 0) {
      throw ParameterError(std::string(volume_only) + " takes no part in a finger set by its pressure: drive the rows "
                           "by volume (--drive volume, drive=\"volume\") to fit it");
    }
  }
  // An incompressible fill: the volume sets every chamber's stretch, and so the shape, whatever the wall's
  // stiffness, which sets only the pressure (docs/MODEL.md, "Volume").
  const bool incompressible = base.dead_volume_m3 == 0.0 && std::count(keys.begin(), keys.end(), "dead_volume_m3") == 0;
  for (const char* pressure_only : {"shear_modulus_pa", "wall_locking_jm"}) {
    if (by_volume && incompressible && !pressure &&
        std::count(keys.begin(), keys.end(), pressure_only) > 0) {
      throw ParameterError(std::string(pressure_only) + " cannot be fitted to shapes set by the volume of an "
                           "incompressible fluid (dead_volume_m3 = 0): the volume alone sets the shape, the modulus "
                           "only the pressure (compare gauge_pa, or fit or give dead_volume_m3)");
    }
  }
  for (const auto& m : data) {
    if (pressure && !m.hasGauge()) {
      throw ParameterError(m.where() + ": no gauge_pa to compare the model's pressure with");
    }
  }
}

// A key the drawing makes is the drawing's: fitted by itself, the written file (the drawing, its keys as comments)
// would not reproduce the fit. Refused, naming the drawing's keys to fit instead; a drawing key needs a drawing.
void checkDrawnKey(const FingerParameters& base, const std::string& key) {
  const bool drawn = !base.drawing.empty();
  if (key.rfind(kDrawingPrefix, 0) == 0 && !drawn) {
    throw ParameterError("parameter '" + key + "' is a drawing's: the parameter file has no drawing (docs/DRAWING.md)");
  }
  const std::vector<std::string>& made = drawnModelKeys();
  if (!drawn || std::find(made.begin(), made.end(), key) == made.end()) return;
  const std::string instead = key == "chamber_height_m"        ? "drawing/cavity_height_m"
                              : key == "chamber_width_m"       ? "drawing/cavity_width_m"
                              : key == "chamber_thickness_m"   ? "drawing/cavity_length_m"
                              : key == "wall_critical_height_m" ? "drawing/roof_thickness_m or drawing/cavity_height_m"
                              : key == "wall_thickness_m"      ? "drawing/wall_thickness_m"
                                                               : "the drawing's sizes (drawing/KEY)";
  throw ParameterError("parameter '" + key + "' is made by the drawing (docs/DRAWING.md), which the written file "
                       "keeps: fit " + instead + " instead");
}

// The keys are fittable, each once, and the data has what @p quantity compares. @throws ParameterError naming it.
void checkKeysAndData(const FingerParameters& base, const std::vector<std::string>& keys,
                      const std::vector<Measurement>& data, CalibrationQuantity quantity) {
  if (keys.empty()) throw ParameterError("calibration fits at least one parameter, got none");
  for (const auto& k : keys) {
    checkDrawnKey(base, k);
    if (!isFittableKey(k)) {
      std::string fittable;
      for (const char* key : kFittable) fittable += (fittable.empty() ? "" : ", ") + std::string(key);
      // A drawing's sizes where the file has a drawing; else what a drawing would add.
      for (const char* key : kFittableDrawn) fittable += base.drawing.empty() ? "" : ", drawing/" + std::string(key);
      throw ParameterError("parameter '" + k + "' cannot be fitted; fittable: " + fittable +
                           (base.drawing.empty() ? " (and a drawing's sizes, drawing/KEY, where the file has a "
                                                   "drawing: docs/DRAWING.md)"
                                                 : ""));
    }
    if (std::count(keys.begin(), keys.end(), k) > 1) throw ParameterError("parameter '" + k + "' given twice");
  }
  const bool uses_joints = quantity == CalibrationQuantity::kOuterAverage ||
                           quantity == CalibrationQuantity::kEveryJoint || quantity == CalibrationQuantity::kFirstJoint;
  checkTheDrive(base, keys, data, quantity);
  for (const auto& m : data) {
    if (m.forceOnly()) {  // its force is compared at its pressure, whatever the shape's comparison
      if (!m.hasGauge()) throw ParameterError(m.where() + ": blocked_tip_force_n without gauge_pa, its pressure");
      continue;
    }
    if (quantity == CalibrationQuantity::kGauge) continue;  // checkTheDrive saw to it
    const bool angle = quantity == CalibrationQuantity::kTipAngle ||
                       quantity == CalibrationQuantity::kTipAngleAndGauge ||
                       quantity == CalibrationQuantity::kGaugeAtTipAngle;
    if (quantity == CalibrationQuantity::kGaugeAtTipAngle && !m.hasGauge()) {
      throw ParameterError(m.where() + ": no gauge_pa to compare the pressure at the measured bend with");
    }
    const bool chord = quantity == CalibrationQuantity::kChordAngle;
    const bool has = uses_joints ? m.hasJoints()
                     : angle     ? m.hasTipAngle() || m.hasJoints()
                     : chord     ? m.hasChordAngle() || m.hasTipPosition() || m.hasJoints()
                                 : m.hasTipPosition() || m.hasJoints();
    if (!has) {
      throw ParameterError(m.where() + ": no measurement for '" + quantityName(quantity) +
                           "' (columns " +
                           (uses_joints ? "joint_1_rad..joint_N_rad"
                            : angle     ? "tip_angle_rad or the joints"
                            : chord     ? "chord_angle_rad, tip_x_m,tip_y_m or the joints"
                                        : "tip_x_m,tip_y_m or the joints") +
                           ")");
    }
    if (m.hasJoints() && m.joint_rad.size() != static_cast<std::size_t>(base.chamber_count)) {
      throw ParameterError(m.where() + ": " + std::to_string(m.joint_rad.size()) +
                           " measured joints, but chamber_count is " + std::to_string(base.chamber_count));
    }
  }
  if (quantity == CalibrationQuantity::kOuterAverage && base.chamber_count < 2) {
    throw ParameterError("the average compares joints 2..N: chamber_count must be >= 2");
  }
}

// What the data cannot determine is refused, not fitted to an arbitrary value. The chamber keys shape theta(P), which
// each pressure measures once (in the model all of a row's joints 2..N are one number): they need more rows than
// keys. base_wall_share scales joint 1 alone, which every row measures besides.
void refuseWhatTheDataCannotTell(const std::vector<std::string>& keys, std::size_t rows, CalibrationQuantity quantity) {
  const bool share = std::count(keys.begin(), keys.end(), "base_wall_share") > 0;
  const std::size_t chamber_keys = keys.size() - (share ? 1 : 0);
  if (chamber_keys >= rows) {
    throw ParameterError(std::to_string(chamber_keys) + " chamber keys from " + std::to_string(rows) +
                         " pressures: a fit needs more pressures than the keys that shape the half angle");
  }
  if (share && quantity == CalibrationQuantity::kOuterAverage) {
    throw ParameterError("base_wall_share cannot be fitted to the joints 2..N average: it moves joint 1 alone, which "
                         "the average leaves out (compare 'joints' instead)");
  }
  if (quantity == CalibrationQuantity::kFirstJoint && chamber_keys > 0) {
    throw ParameterError("joint 1 alone cannot fit chamber keys apart from base_wall_share: both scale it (compare "
                         "'joints' instead)");
  }
  if (share && keys.size() > 1 &&
      (quantity == CalibrationQuantity::kTipAngle || quantity == CalibrationQuantity::kTipPosition ||
       quantity == CalibrationQuantity::kChordAngle || quantity == CalibrationQuantity::kTipAngleAndGauge ||
       quantity == CalibrationQuantity::kGaugeAtTipAngle)) {
    throw ParameterError("base_wall_share cannot be fitted with other keys to tip data alone: the tip cannot tell "
                         "the base face's share of the bending from the chambers' (measure the joints, or fit it "
                         "alone)");
  }
}

// Every joint with base_wall_share and chamber keys: each key to the joints it moves. The chamber keys to the joints
// 2..N average, then base_wall_share to joint 1.
CalibrationResult calibrateEveryJointInTwoSteps(const FingerParameters& base, const std::vector<std::string>& keys,
                                                const std::vector<Measurement>& data, CalibrationObjective objective,
                                                const CalibrationProgress& progress) {
  std::vector<std::string> chamber;
  for (const auto& k : keys) {
    if (k != "base_wall_share") chamber.push_back(k);
  }
  const CalibrationResult outer =
      calibrate(base, chamber, data, objective, CalibrationQuantity::kOuterAverage, progress);
  CalibrationResult both = calibrate(outer.parameters, {"base_wall_share"}, data, objective,
                                     CalibrationQuantity::kFirstJoint, progress);
  both.model_evaluations += outer.model_evaluations;
  both.keys = keys;
  both.values.clear();
  for (const auto& k : keys) {
    both.values.push_back(k == "base_wall_share" ? both.parameters.base_wall_share
                                                 : outer.values[static_cast<std::size_t>(
                                                       std::find(chamber.begin(), chamber.end(), k) - chamber.begin())]);
  }
  // Over every joint, as for any fit.
  both.objective_value = objectiveOver(both.residuals, CalibrationQuantity::kEveryJoint, objective);
  return both;
}

// The fit itself: the solver's best point over the keys' search box (solver.hpp), reported in the caller's key order.
CalibrationResult searchKeys(const FingerParameters& base, const std::vector<std::string>& keys,
                             const std::vector<Measurement>& data, CalibrationObjective objective,
                             CalibrationQuantity quantity, const CalibrationProgress& progress, ScanRecord* record) {
  const FitProblem problem(base, keys, data, quantity, progress);
  const FitSolution best = solveFit(problem, objective, record);
  CalibrationResult result;
  result.parameters = problem.parametersAt(best.u);
  result.keys = keys;
  result.values = problem.valuesAt(best.u);
  result.objective_value = best.objective;
  result.model_evaluations = problem.evaluations();
  result.residuals = residuals(result.parameters, data, quantity);
  return result;
}

}  // namespace

CalibrationResult calibrate(const FingerParameters& base, const std::vector<std::string>& keys,
                            const std::vector<Measurement>& data, CalibrationObjective objective,
                            CalibrationQuantity quantity, const CalibrationProgress& progress) {
  return calibrateKeepingScan(base, keys, data, objective, quantity, progress, nullptr);
}

CalibrationResult calibrateKeepingScan(const FingerParameters& base, const std::vector<std::string>& keys,
                                       const std::vector<Measurement>& data, CalibrationObjective objective,
                                       CalibrationQuantity quantity, const CalibrationProgress& progress,
                                       ScanRecord* record, bool uncertainty) {
  checkKeysAndData(base, keys, data, quantity);
  refuseWhatTheDataCannotTell(keys, data.size(), quantity);
  const bool share = std::count(keys.begin(), keys.end(), "base_wall_share") > 0;
  CalibrationResult result = share && keys.size() > 1 && quantity == CalibrationQuantity::kEveryJoint
                                 ? calibrateEveryJointInTwoSteps(base, keys, data, objective, progress)
                                 : searchKeys(base, keys, data, objective, quantity, progress, record);
  if (uncertainty) calibrationUncertainty(base, data, quantity, objective, result);
  return result;
}

double leaveOneOutObjective(const std::vector<Residual>& leave_one_out, CalibrationQuantity quantity,
                            CalibrationObjective objective) {
  return objectiveOver(leave_one_out, quantity, objective);
}

namespace {

// The fit's residual scatter: the standard error sqrt(sum e^2 / (n - k)) over the rows that measured the quantity,
// k the fitted keys (a fit of k keys to n rows leaves n - k of the noise in its residuals); 0 without rows.
double residualScatter(const std::vector<Residual>& fit, std::size_t fitted_keys, double (*error)(const Residual&)) {
  double sum = 0.0;
  std::size_t n = 0;
  for (const Residual& r : fit) {
    const double e = error(r);
    if (std::isnan(e)) continue;
    sum += e * e;
    ++n;
  }
  const std::size_t dof = n > fitted_keys ? n - fitted_keys : 1;
  return n == 0 ? 0.0 : std::sqrt(sum / static_cast<double>(dof));
}

double angleError(const Residual& r) { return r.tip_angle_error_rad(); }
double positionError(const Residual& r) { return r.tip_position_error_m(); }

}  // namespace

TipUncertainty tipUncertainty(const std::vector<Residual>& fit, const std::vector<Residual>& leave_one_out,
                              std::size_t fitted_keys, double held_out_scale) {
  if (fit.size() != leave_one_out.size()) throw ParameterError("tipUncertainty: fit and leave-one-out rows differ");
  std::vector<std::size_t> order(fit.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&fit](std::size_t a, std::size_t b) { return fit[a].gauge_pa < fit[b].gauge_pa; });
  // No bar below the noise the fit leaves: a row the fit happens to hit is no better measured than the others.
  const double angle_floor = residualScatter(fit, fitted_keys, angleError);
  const double position_floor = residualScatter(fit, fitted_keys, positionError);
  std::vector<double> gauge, angle, position;
  for (std::size_t i : order) {
    if (!(fit[i].gauge_pa > 0.0)) continue;  // the rest shape needs no error bar
    const double a = std::max({std::fabs(fit[i].tip_angle_error_rad()),
                               held_out_scale * std::fabs(leave_one_out[i].tip_angle_error_rad()), angle_floor});
    const double x = std::max({fit[i].tip_position_error_m(), held_out_scale * leave_one_out[i].tip_position_error_m(),
                               position_floor});
    const double angle_bar = std::isnan(fit[i].tip_angle_error_rad()) ? std::nan("") : a;  // NaN: not measured
    const double position_bar = std::isnan(fit[i].tip_position_error_m()) ? std::nan("") : x;
    // Neither bar: the row measured no tip, or the fitted model has no shape at its pressure (beyond its limit
    // point, where it publishes none): no bar to write there.
    if (std::isnan(angle_bar) && std::isnan(position_bar)) continue;
    if (!gauge.empty() && fit[i].gauge_pa == gauge.back()) {  // repeated pressure: keep the larger bar
      angle.back() = std::fmax(angle.back(), angle_bar);
      position.back() = std::fmax(position.back(), position_bar);
      continue;
    }
    gauge.push_back(fit[i].gauge_pa);
    angle.push_back(angle_bar);
    position.push_back(position_bar);
  }
  return TipUncertainty::fromLists(gauge, angle, position, "calibration");
}

std::string unpredictedRowsWarning(const std::vector<Residual>& fit, const std::vector<Residual>& leave_one_out) {
  const auto unpredicted = [](double fitted, double held_out) { return !std::isnan(fitted) && std::isnan(held_out); };
  std::ostringstream rows;
  std::size_t count = 0;
  for (std::size_t i = 0; i < fit.size() && i < leave_one_out.size(); ++i) {
    if (!(fit[i].gauge_pa > 0.0)) continue;
    if (!unpredicted(fit[i].tip_angle_error_rad(), leave_one_out[i].tip_angle_error_rad()) &&
        !unpredicted(fit[i].tip_position_error_m(), leave_one_out[i].tip_position_error_m())) {
      continue;
    }
    rows << (count++ == 0 ? "" : ", ") << fit[i].gauge_pa;
  }
  if (count == 0) return "";
  return "leave-one-out: " + std::to_string(count) + " row(s) (gauge_pa " + rows.str() +
         ") have no prediction: the model fitted without each has no shape at its pressure (beyond its limit "
         "point), so their tip error bars take the fit's error alone and may be too small there";
}

std::vector<Residual> leaveOneOut(const FingerParameters& base, const std::vector<std::string>& keys,
                                  const std::vector<Measurement>& data, CalibrationObjective objective,
                                  CalibrationQuantity quantity, const CalibrationProgress& progress,
                                  const std::string& step) {
  return leaveOneOutFromScan(base, keys, data, objective, quantity, progress, step, ScanRecord());
}

std::vector<Residual> leaveOneOutFromScan(const FingerParameters& base, const std::vector<std::string>& keys,
                                          const std::vector<Measurement>& data, CalibrationObjective objective,
                                          CalibrationQuantity quantity, const CalibrationProgress& progress,
                                          const std::string& step, ScanRecord record) {
  std::vector<std::size_t> fold_of_row(data.size());
  for (std::size_t i = 0; i < data.size(); ++i) fold_of_row[i] = i;
  return heldOutFromScan(base, keys, data, objective, quantity, progress, step, std::move(record), fold_of_row);
}

namespace {

// Reports a long run's folds to @p progress from several threads, one at a time.
class FoldListener {
 public:
  explicit FoldListener(const CalibrationProgress& progress) : progress_(progress) {}
  CalibrationProgress operator()(const std::string& prefix) {
    if (!progress_) return {};
    return [this, prefix](const std::string& s) {
      const std::lock_guard<std::mutex> lock(mutex_);
      progress_(prefix + s);
    };
  }

 private:
  const CalibrationProgress& progress_;
  std::mutex mutex_;
};

}  // namespace

std::vector<Residual> heldOutFromScan(const FingerParameters& base, const std::vector<std::string>& keys,
                                      const std::vector<Measurement>& data, CalibrationObjective objective,
                                      CalibrationQuantity quantity, const CalibrationProgress& progress,
                                      const std::string& step, ScanRecord record,
                                      const std::vector<std::size_t>& fold_of_row) {
  const std::size_t chamber_keys =
      keys.size() - static_cast<std::size_t>(std::count(keys.begin(), keys.end(), std::string("base_wall_share")));
  if (data.size() < chamber_keys + 2) {
    throw ParameterError(std::to_string(data.size()) + " rows; fitting " + std::to_string(chamber_keys) +
                         " chamber keys with leave-one-out needs at least " + std::to_string(chamber_keys + 2));
  }
  checkKeysAndData(base, keys, data, quantity);
  const bool two_steps = std::count(keys.begin(), keys.end(), "base_wall_share") > 0 && keys.size() > 1 &&
                         quantity == CalibrationQuantity::kEveryJoint;
  FoldListener heard(progress);
  // One scan of every row (the fit's, where given); each fold starts from its best points measured without the
  // held-out rows.
  const FitProblem full(base, keys, data, quantity, heard(step + ", the scan: "));
  if (!two_steps && record.points.empty()) scanInto(full, objective, record);
  const std::size_t folds = fold_of_row.empty() ? 0 : *std::max_element(fold_of_row.begin(), fold_of_row.end()) + 1;
  std::vector<Residual> predicted(data.size());
  onEveryCore(folds, [&](std::size_t f) {
    const std::string name = step + ", " + (folds == data.size() ? "row " : "fold ") + std::to_string(f + 1) + " of " +
                             std::to_string(folds) + ": ";
    std::vector<Measurement> others, held;
    std::vector<bool> kept(full.termCount(), true);
    for (std::size_t i = 0; i < data.size(); ++i) {
      (fold_of_row[i] == f ? held : others).push_back(data[i]);
      if (fold_of_row[i] == f) std::fill_n(kept.begin() + static_cast<long>(full.firstTermOf(i)), full.termCountOf(i), false);
    }
    FingerParameters without;
    if (two_steps) {  // every joint with the base face's share: fitted in two steps, each fold in full
      without = calibrate(base, keys, others, objective, quantity, heard(name)).parameters;
    } else {
      const FitProblem fold(base, keys, others, quantity, heard(name));
      without = fold.parametersAt(solveFold(fold, objective, record, kept).u);
    }
    const std::vector<Residual> rows = residuals(without, held, quantity);
    for (std::size_t i = 0, k = 0; i < data.size(); ++i) {
      if (fold_of_row[i] == f) predicted[i] = rows[k++];
    }
  });
  return predicted;
}

}  // namespace pneumatic_finger
