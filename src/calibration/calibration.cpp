#include "pneumatic_finger/calibration/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>

#include "fit_problem.hpp"
#include "fit_space.hpp"
#include "solver.hpp"

namespace pneumatic_finger {

CalibrationObjective parseObjective(const std::string& name) {
  if (name == "minimax") return CalibrationObjective::kMinimax;
  if (name == "least_squares") return CalibrationObjective::kLeastSquares;
  throw ParameterError("unknown objective '" + name + "'; known: minimax, least_squares");
}

const char* objectiveName(CalibrationObjective objective) {
  return objective == CalibrationObjective::kMinimax ? "minimax" : "least_squares";
}

CalibrationQuantity parseQuantity(const std::string& name) {
  for (CalibrationQuantity q : {CalibrationQuantity::kOuterAverage, CalibrationQuantity::kEveryJoint,
                                CalibrationQuantity::kFirstJoint, CalibrationQuantity::kTipAngle,
                                CalibrationQuantity::kTipPosition, CalibrationQuantity::kGauge,
                                CalibrationQuantity::kTipAngleAndGauge}) {
    if (name == quantityName(q)) return q;
  }
  throw ParameterError("unknown quantity '" + name + "'; known: average, joints, joint_1, tip_angle, tip_position, "
                       "gauge_pa, tip_angle+gauge_pa");
}

const char* quantityName(CalibrationQuantity quantity) {
  switch (quantity) {
    case CalibrationQuantity::kOuterAverage: return "average";
    case CalibrationQuantity::kEveryJoint: return "joints";
    case CalibrationQuantity::kFirstJoint: return "joint_1";
    case CalibrationQuantity::kTipAngle: return "tip_angle";
    case CalibrationQuantity::kTipPosition: return "tip_position";
    case CalibrationQuantity::kGauge: return "gauge_pa";
    case CalibrationQuantity::kTipAngleAndGauge: return "tip_angle+gauge_pa";
  }
  return "average";
}

CalibrationQuantity defaultQuantity(const std::vector<Measurement>& data) {
  if (data.empty()) throw ParameterError("no measurements");
  if (data.front().hasJoints()) return CalibrationQuantity::kEveryJoint;
  if (data.front().hasTipPosition()) return CalibrationQuantity::kTipPosition;
  return CalibrationQuantity::kTipAngle;
}

std::vector<std::string> defaultFitKeys(CalibrationQuantity quantity, WallLaw law) {
  if (quantity == CalibrationQuantity::kEveryJoint) return {"shear_modulus_pa", "chamber_gap_m", "base_wall_share"};
  if (quantity == CalibrationQuantity::kFirstJoint) return {"base_wall_share"};
  // The thick wall keeps the file's J_m: its Gent pressure costs about twice the membrane's, and a third nested key
  // with leave-one-out took ten minutes on the ribbed segment's 15 rows. Name wall_locking_jm with --fit to fit it.
  if (law == WallLaw::kMembrane) return {"shear_modulus_pa", "chamber_gap_m", "wall_locking_jm"};
  return {"shear_modulus_pa", "chamber_gap_m"};
}

std::vector<double> Residual::terms(CalibrationQuantity quantity) const {
  switch (quantity) {
    case CalibrationQuantity::kOuterAverage: return {error_rad()};
    case CalibrationQuantity::kEveryJoint: {
      std::vector<double> e(model_joint_rad.size());
      for (std::size_t k = 0; k < e.size(); ++k) e[k] = model_joint_rad[k] - measured_joint_rad[k];
      return e;
    }
    case CalibrationQuantity::kFirstJoint: return {joint1_error_rad()};
    case CalibrationQuantity::kTipAngle: return {tip_angle_error_rad()};
    case CalibrationQuantity::kTipPosition: return {tip_position_error_m()};
    case CalibrationQuantity::kGauge: return {gauge_error_pa()};
    case CalibrationQuantity::kTipAngleAndGauge:
      // One radian of bend weighs as the whole pressure: a scale both errors share, with no unit to choose.
      if (measured_gauge_pa == 0.0) return {tip_angle_error_rad()};
      return {tip_angle_error_rad(), gauge_relative_error()};
  }
  return {};
}

bool isFittableKey(const std::string& key) {
  return std::find(std::begin(kFittable), std::end(kFittable), key) != std::end(kFittable);
}

namespace {

// What was measured of a row, into @p r: the joints (and the tip they make along the model's segments, eq 38), the
// tip angle and position where the file gives them.
void measuredInto(const FingerParameters& parameters, const Measurement& m, Residual& r) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  r.measured_avg_rad = r.measured_joint1_rad = r.measured_tip_angle_rad = nan;
  r.measured_tip_x_m = r.measured_tip_y_m = nan;
  if (m.hasJoints()) {
    r.measured_joint_rad = m.joint_rad;
    r.measured_avg_rad = m.averageOuterJoints();
    r.measured_joint1_rad = m.joint_rad[0];
    double angle = 0.0;
    for (std::size_t k = 0; k < m.joint_rad.size() && k < parameters.segment_length_m.size(); ++k) {
      angle += m.joint_rad[k];
    }
    const Eigen::Vector2d tip = tipOfJoints(parameters, m.joint_rad);
    r.measured_tip_angle_rad = angle;
    r.measured_tip_x_m = tip.x();
    r.measured_tip_y_m = tip.y();
  }
  if (m.hasTipAngle()) r.measured_tip_angle_rad = m.tip_angle_rad;
  if (m.hasTipPosition()) {
    r.measured_tip_x_m = m.tip_x_m;
    r.measured_tip_y_m = m.tip_y_m;
  }
}

}  // namespace

std::vector<Residual> residuals(const FingerParameters& parameters, const std::vector<Measurement>& data) {
  ModelOptions options;
  options.wall_inverse = false;  // one model per candidate, a few dozen rows each: the inverse's build would dominate
  FingerModel model(parameters, options);
  FingerWorkspace ws(model);
  std::vector<Residual> out;
  const int n = parameters.chamber_count;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  FingerState none = restState(parameters);  // what a row beyond the limit point gets: NaN, no shape
  none.joint_angle_rad.setConstant(nan);
  none.backbone_m.setConstant(nan);
  none.tip_angle_rad = nan;
  none.gauge_pa = nan;
  for (const Measurement& m : data) {
    // The rows in order, as a path: a wall past its limit point snaps to its far branch where it has one, and such a
    // row is data like any other (docs/MODEL.md, "The snap-through"). A row set by its volume has a shape before, at
    // and past the limit point, and the model's pressure there is compared with the measured.
    const FingerState& evaluated =
        m.driven_by_volume ? model.evaluateVolume(m.supplied_volume_m3, ws) : model.evaluate(m.gauge_pa, ws);
    const bool shaped = evaluated.status == EvaluationStatus::kOk || evaluated.status == EvaluationStatus::kVacuum ||
                        evaluated.status == EvaluationStatus::kSnappedThrough;
    const FingerState& s = shaped ? evaluated : none;
    Residual r;
    r.measured_gauge_pa = m.gauge_pa;
    r.model_gauge_pa = m.driven_by_volume ? s.gauge_pa : m.gauge_pa;
    r.gauge_pa = m.hasGauge() ? m.gauge_pa : r.model_gauge_pa;
    r.supplied_volume_m3 = m.supplied_volume_m3;
    r.model_joint_rad.assign(s.joint_angle_rad.data(), s.joint_angle_rad.data() + n);
    r.model_avg_rad = n > 1 ? s.joint_angle_rad.tail(n - 1).mean() : nan;
    r.model_joint1_rad = s.joint_angle_rad[0];
    r.model_tip_angle_rad = s.tip_angle_rad;
    r.model_tip_x_m = s.tip().x();
    r.model_tip_y_m = s.tip().y();
    measuredInto(parameters, m, r);
    out.push_back(std::move(r));
  }
  return out;
}

namespace {

// The objective over @p rows: the largest |term| (minimax) or the sum of squared terms, the terms being what
// @p quantity compares in each row.
double objectiveOver(const std::vector<Residual>& rows, CalibrationQuantity quantity, CalibrationObjective objective) {
  double value = 0.0;
  for (const Residual& r : rows) {
    for (double e : r.terms(quantity)) {
      if (std::isnan(e)) return std::numeric_limits<double>::infinity();  // a row the model gives no shape for
      value = objective == CalibrationObjective::kMinimax ? std::max(value, std::fabs(e)) : value + e * e;
    }
  }
  return value;
}

}  // namespace

namespace {

// What the drive needs: the pressure against the volume and the dead gas are seen only when the rows are set by
// their volume (under pressure the model's pressure is the measured, and the gas takes no part in the shape).
void checkTheDrive(const FingerParameters& base, const std::vector<std::string>& keys,
                   const std::vector<Measurement>& data, CalibrationQuantity quantity) {
  const bool by_volume = !data.empty() && data.front().driven_by_volume;
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

// The keys are fittable, each once, and the data has what @p quantity compares. @throws ParameterError naming it.
void checkKeysAndData(const FingerParameters& base, const std::vector<std::string>& keys,
                      const std::vector<Measurement>& data, CalibrationQuantity quantity) {
  if (keys.empty()) throw ParameterError("calibration fits at least one parameter, got none");
  for (const auto& k : keys) {
    if (!isFittableKey(k)) {
      std::string fittable;
      for (const char* key : kFittable) fittable += (fittable.empty() ? "" : ", ") + std::string(key);
      throw ParameterError("parameter '" + k + "' cannot be fitted; fittable: " + fittable);
    }
    if (std::count(keys.begin(), keys.end(), k) > 1) throw ParameterError("parameter '" + k + "' given twice");
  }
  const bool uses_joints = quantity == CalibrationQuantity::kOuterAverage ||
                           quantity == CalibrationQuantity::kEveryJoint || quantity == CalibrationQuantity::kFirstJoint;
  checkTheDrive(base, keys, data, quantity);
  for (const auto& m : data) {
    if (quantity == CalibrationQuantity::kGauge) continue;  // checkTheDrive saw to it
    const bool angle = quantity == CalibrationQuantity::kTipAngle || quantity == CalibrationQuantity::kTipAngleAndGauge;
    const bool has = uses_joints ? m.hasJoints()
                     : angle     ? m.hasTipAngle() || m.hasJoints()
                                 : m.hasTipPosition() || m.hasJoints();
    if (!has) {
      throw ParameterError(m.where() + ": no measurement for '" + quantityName(quantity) +
                           "' (columns " +
                           (uses_joints ? "joint_1_rad..joint_N_rad"
                            : angle     ? "tip_angle_rad or the joints"
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
       quantity == CalibrationQuantity::kTipAngleAndGauge)) {
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
                             CalibrationQuantity quantity, const CalibrationProgress& progress) {
  const FitProblem problem(base, keys, data, quantity, progress);
  const FitSolution best = solveFit(problem, objective);
  CalibrationResult result;
  result.parameters = problem.parametersAt(best.u);
  result.keys = keys;
  result.values = problem.valuesAt(best.u);
  result.objective_value = best.objective;
  result.model_evaluations = problem.evaluations();
  result.residuals = residuals(result.parameters, data);
  return result;
}

}  // namespace

CalibrationResult calibrate(const FingerParameters& base, const std::vector<std::string>& keys,
                            const std::vector<Measurement>& data, CalibrationObjective objective,
                            CalibrationQuantity quantity, const CalibrationProgress& progress) {
  checkKeysAndData(base, keys, data, quantity);
  refuseWhatTheDataCannotTell(keys, data.size(), quantity);
  const bool share = std::count(keys.begin(), keys.end(), "base_wall_share") > 0;
  CalibrationResult result = share && keys.size() > 1 && quantity == CalibrationQuantity::kEveryJoint
                                 ? calibrateEveryJointInTwoSteps(base, keys, data, objective, progress)
                                 : searchKeys(base, keys, data, objective, quantity, progress);
  calibrationUncertainty(base, data, quantity, result);
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
                              std::size_t fitted_keys) {
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
    const double a = std::max({std::fabs(fit[i].tip_angle_error_rad()), std::fabs(leave_one_out[i].tip_angle_error_rad()),
                               angle_floor});
    const double x = std::max({fit[i].tip_position_error_m(), leave_one_out[i].tip_position_error_m(), position_floor});
    const double angle_bar = std::isnan(fit[i].tip_angle_error_rad()) ? std::nan("") : a;  // NaN: not measured
    const double position_bar = std::isnan(fit[i].tip_position_error_m()) ? std::nan("") : x;
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

std::vector<Residual> leaveOneOut(const FingerParameters& base, const std::vector<std::string>& keys,
                                  const std::vector<Measurement>& data, CalibrationObjective objective,
                                  CalibrationQuantity quantity, const CalibrationProgress& progress,
                                  const std::string& step) {
  const std::size_t chamber_keys =
      keys.size() - static_cast<std::size_t>(std::count(keys.begin(), keys.end(), std::string("base_wall_share")));
  if (data.size() < chamber_keys + 2) {
    throw ParameterError(std::to_string(data.size()) + " rows; fitting " + std::to_string(chamber_keys) +
                         " chamber keys with leave-one-out needs at least " + std::to_string(chamber_keys + 2));
  }
  std::vector<Residual> predicted;
  for (std::size_t i = 0; i < data.size(); ++i) {
    const std::string row = step + ", row " + std::to_string(i + 1) + " of " + std::to_string(data.size()) + ": ";
    std::vector<Measurement> others = data;
    others.erase(others.begin() + static_cast<long>(i));
    const CalibrationResult without = calibrate(base, keys, others, objective, quantity,
                                                progress ? CalibrationProgress([&](const std::string& s) { progress(row + s); })
                                                         : CalibrationProgress());
    predicted.push_back(residuals(without.parameters, {data[i]})[0]);
  }
  return predicted;
}

}  // namespace pneumatic_finger
