// What a calibration compares (calibration.hpp): the quantities, each row's residual, and the quantity a data set
// asks for by default.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pneumatic_finger/calibration/calibration.hpp"
#include "pneumatic_finger/core/chord_angle.hpp"

namespace pneumatic_finger {

CalibrationQuantity parseQuantity(const std::string& name) {
  for (CalibrationQuantity q : {CalibrationQuantity::kOuterAverage, CalibrationQuantity::kEveryJoint,
                                CalibrationQuantity::kFirstJoint, CalibrationQuantity::kTipAngle,
                                CalibrationQuantity::kTipPosition, CalibrationQuantity::kChordAngle,
                                CalibrationQuantity::kGauge,
                                CalibrationQuantity::kTipAngleAndGauge, CalibrationQuantity::kGaugeAtTipAngle}) {
    if (name == quantityName(q)) return q;
  }
  throw ParameterError("unknown quantity '" + name + "'; known: average, joints, joint_1, tip_angle, tip_position, "
                       "chord_angle, gauge_pa, tip_angle+gauge_pa, gauge_at_tip_angle");
}

const char* quantityName(CalibrationQuantity quantity) {
  switch (quantity) {
    case CalibrationQuantity::kOuterAverage: return "average";
    case CalibrationQuantity::kEveryJoint: return "joints";
    case CalibrationQuantity::kFirstJoint: return "joint_1";
    case CalibrationQuantity::kTipAngle: return "tip_angle";
    case CalibrationQuantity::kTipPosition: return "tip_position";
    case CalibrationQuantity::kChordAngle: return "chord_angle";
    case CalibrationQuantity::kGauge: return "gauge_pa";
    case CalibrationQuantity::kTipAngleAndGauge: return "tip_angle+gauge_pa";
    case CalibrationQuantity::kGaugeAtTipAngle: return "gauge_at_tip_angle";
  }
  return "average";
}

bool bendLeaps(const std::vector<Measurement>& data) {
  std::vector<std::pair<double, double>> rows;  // (pressure, bend) of the rows set by their pressure
  for (const Measurement& m : data) {
    if (!m.driven_by_volume && m.hasGauge() && m.hasTipAngle()) rows.emplace_back(m.gauge_pa, m.tip_angle_rad);
  }
  if (rows.size() < 4) return false;
  std::sort(rows.begin(), rows.end());
  double low = rows.front().second, high = low;
  for (const auto& r : rows) low = std::min(low, r.second), high = std::max(high, r.second);
  const double range_pa = rows.back().first - rows.front().first, mean_slope = (high - low) / range_pa;
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    // Within the window, or from one row to the next where the rows lie farther apart than it.
    const double window_pa = std::max(kLeapWindow * range_pa, rows[i + 1].first - rows[i].first);
    for (std::size_t j = i + 1; j < rows.size() && rows[j].first - rows[i].first <= window_pa; ++j) {
      const double rise = rows[j].second - rows[i].second, span_pa = rows[j].first - rows[i].first;
      if (rise >= kLeapShare * (high - low) && rise > kLeapSteepness * mean_slope * span_pa) return true;
    }
  }
  return false;
}

CalibrationQuantity defaultQuantity(const std::vector<Measurement>& data) {
  if (data.empty()) throw ParameterError("no measurements");
  // The first row that measured a shape says what the rows have (rows of blocked force alone join any comparison).
  const auto shaped = std::find_if(data.begin(), data.end(), [](const Measurement& m) { return !m.forceOnly(); });
  const Measurement& first = shaped != data.end() ? *shaped : data.front();
  if (first.hasJoints()) return CalibrationQuantity::kEveryJoint;
  if (first.hasTipPosition()) return CalibrationQuantity::kTipPosition;
  if (!first.hasTipAngle() && first.hasChordAngle()) return CalibrationQuantity::kChordAngle;
  return bendLeaps(data) ? CalibrationQuantity::kGaugeAtTipAngle : CalibrationQuantity::kTipAngle;
}

std::vector<std::string> defaultFitKeys(CalibrationQuantity quantity, WallLaw law) {
  if (quantity == CalibrationQuantity::kEveryJoint) return {"shear_modulus_pa", "chamber_gap_m", "base_wall_share"};
  if (quantity == CalibrationQuantity::kFirstJoint) return {"base_wall_share"};
  // The thick wall keeps the file's J_m: fitting it lowers the fit's error but not always the prediction's, so
  // --wall-law auto adds it only where it predicts clearly better (model_selection.cpp).
  if (law == WallLaw::kMembrane) return {"shear_modulus_pa", "chamber_gap_m", "wall_locking_jm"};
  return {"shear_modulus_pa", "chamber_gap_m"};
}

std::vector<double> Residual::terms(CalibrationQuantity quantity) const {
  // The blocked force, where measured, joins the row's shape terms: its error as a share of the data's largest force.
  std::vector<double> out = force_only ? std::vector<double>{} : shapeTerms(quantity);
  if (!std::isnan(measured_blocked_force_n)) out.push_back(blocked_force_error_n() / force_scale_n);
  return out;
}

std::vector<double> Residual::shapeTerms(CalibrationQuantity quantity) const {
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
    case CalibrationQuantity::kChordAngle: return {chord_angle_error_rad()};
    case CalibrationQuantity::kGauge: return {gauge_error_pa()};
    case CalibrationQuantity::kTipAngleAndGauge:
      // One radian of bend weighs as the whole pressure: a scale both errors share, with no unit to choose.
      if (measured_gauge_pa == 0.0) return {tip_angle_error_rad()};
      return {tip_angle_error_rad(), gauge_relative_error()};
    case CalibrationQuantity::kGaugeAtTipAngle:
      // A bend of zero or less has no one pressure (any below the walls' first contact gives it): no term.
      if (!(measured_tip_angle_rad > 0.0) || std::isnan(measured_gauge_pa)) return {};
      return {gauge_at_tip_angle_error_pa()};
  }
  return {};
}

namespace {

// What was measured of a row, into @p r: the joints (and the tip they make along the model's segments, eq 38), the
// tip angle and position where the file gives them, and the chord angle: measured, or the measured tip's.
void measuredInto(const FingerParameters& parameters, const Measurement& m, Residual& r) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  r.measured_avg_rad = r.measured_joint1_rad = r.measured_tip_angle_rad = r.measured_chord_angle_rad = nan;
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
  // A tip angle, where one is known, picks the chord's turn; without one, the line's own direction.
  if (!std::isnan(r.measured_tip_x_m)) {
    r.measured_chord_angle_rad = chordAngleRad(r.measured_tip_x_m, r.measured_tip_y_m, r.measured_tip_angle_rad);
  }
  if (m.hasChordAngle()) r.measured_chord_angle_rad = m.chord_angle_rad;
  r.measured_blocked_force_n = m.blocked_tip_force_n;
  r.force_only = m.forceOnly();
}

// The scale of the force terms: the rows' own (setForceScale), else the largest measured blocked force of @p data.
double forceScaleN(const std::vector<Measurement>& data) {
  double largest = 0.0;
  for (const Measurement& m : data) {
    if (!std::isnan(m.force_scale_n)) return m.force_scale_n;
    if (m.hasBlockedForce()) largest = std::max(largest, std::fabs(m.blocked_tip_force_n));
  }
  return largest > 0.0 ? largest : 1.0;
}

}  // namespace

void setForceScale(std::vector<Measurement>& data) {
  for (Measurement& m : data) m.force_scale_n = NAN;
  const double scale = forceScaleN(data);
  for (Measurement& m : data) m.force_scale_n = scale;
}

namespace {

// The pressure of the model's equilibrium at @p tip_angle_rad: the state that holds this bend (the volume that gives
// it, volumeForTipAngle), and that state's pressure. One number per bend on either side of the limit point, the
// unstable stretch between them included, where under pressure control the bend leaps; NaN where no state holds it.
double gaugeOnThePath(const FingerModel& model, double tip_angle_rad, FingerWorkspace& ws) {
  double volume_m3 = 0.0;
  std::string why;
  if (!(tip_angle_rad > 0.0) ||
      !model.volumeForTipAngle(tip_angle_rad, std::numeric_limits<double>::infinity(), volume_m3, why)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const FingerState& s = model.evaluateVolume(volume_m3, ws);
  const bool shaped = s.status == EvaluationStatus::kOk || s.status == EvaluationStatus::kSnappedThrough;
  return shaped ? s.gauge_pa : std::numeric_limits<double>::quiet_NaN();
}

bool shaped(EvaluationStatus status) {
  return status == EvaluationStatus::kOk || status == EvaluationStatus::kVacuum ||
         status == EvaluationStatus::kSnappedThrough;
}

// The model's side of every row, the rows in order as one path: a wall past its limit point snaps to its far branch
// where it has one, and such a row is data like any other (docs/MODEL.md, "The snap-through"). A row set by its
// volume has a shape before, at and past the limit point, and the model's pressure there is compared with the
// measured. NaN where a row has no shape (beyond the limit point, clamped).
struct ModelRows {
  std::size_t points = 0;                                 // backbone points per row: N + 2
  std::vector<double> joint_rad, backbone_m, tip_angle_rad, gauge_pa;  // rows x N, rows x points x 2, rows, rows
};

// Rows set by their pressure all at once (evaluateMany: evaluate()'s numbers bit for bit, in SIMD packs where the
// chambers are identical), else one at a time.
ModelRows modelRows(const FingerModel& model, const std::vector<Measurement>& data) {
  const auto n = static_cast<std::size_t>(model.parameters().chamber_count), rows = data.size();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ModelRows out;
  out.points = n + 2;
  out.joint_rad.assign(rows * n, nan);
  out.backbone_m.assign(rows * out.points * 2, nan);
  out.tip_angle_rad.assign(rows, nan);
  out.gauge_pa.assign(rows, nan);
  FingerWorkspace ws(model);
  std::vector<std::uint8_t> status(rows);
  if (std::none_of(data.begin(), data.end(), [](const Measurement& m) { return m.driven_by_volume; })) {
    for (std::size_t i = 0; i < rows; ++i) out.gauge_pa[i] = data[i].gauge_pa;
    model.evaluateMany(out.gauge_pa.data(), rows,
                       {nullptr, nullptr, nullptr, out.joint_rad.data(), out.backbone_m.data(), out.tip_angle_rad.data(),
                        status.data()},
                       ws);
  } else {
    for (std::size_t i = 0; i < rows; ++i) {
      const Measurement& m = data[i];
      const FingerState& s = m.driven_by_volume ? model.evaluateVolume(m.supplied_volume_m3, ws)
                                                : model.evaluate(m.gauge_pa, ws);
      status[i] = static_cast<std::uint8_t>(s.status);
      std::copy(s.joint_angle_rad.data(), s.joint_angle_rad.data() + n, out.joint_rad.begin() + i * n);
      for (std::size_t k = 0; k < out.points; ++k) {
        out.backbone_m[(i * out.points + k) * 2] = s.backbone_m(0, static_cast<Eigen::Index>(k));
        out.backbone_m[(i * out.points + k) * 2 + 1] = s.backbone_m(1, static_cast<Eigen::Index>(k));
      }
      out.tip_angle_rad[i] = s.tip_angle_rad;
      out.gauge_pa[i] = s.gauge_pa;
    }
  }
  for (std::size_t i = 0; i < rows; ++i) {
    if (shaped(static_cast<EvaluationStatus>(status[i]))) continue;
    std::fill_n(out.joint_rad.begin() + i * n, n, nan);
    std::fill_n(out.backbone_m.begin() + i * out.points * 2, out.points * 2, nan);
    out.tip_angle_rad[i] = out.gauge_pa[i] = nan;
  }
  return out;
}

}  // namespace

std::vector<Residual> residuals(const FingerParameters& parameters, const std::vector<Measurement>& data,
                                CalibrationQuantity quantity) {
  ModelOptions options;
  options.wall_inverse = false;  // one model per candidate, a few dozen rows each: the inverse's build would dominate
  options.snap_point = false;    // nor is its snap asked
  const FingerModel model(parameters, options);
  const ModelRows rows = modelRows(model, data);
  std::optional<FingerWorkspace> inverse;  // only where the pressure on the path is compared
  if (quantity == CalibrationQuantity::kGaugeAtTipAngle) inverse.emplace(model);
  const auto n = static_cast<std::size_t>(parameters.chamber_count);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double force_scale_n = forceScaleN(data);
  Eigen::VectorXd joints(static_cast<Eigen::Index>(n));  // a row's, as a state holds them (the same sum's order)
  std::vector<Residual> out;
  out.reserve(data.size());
  for (std::size_t i = 0; i < data.size(); ++i) {
    const Measurement& m = data[i];
    std::copy_n(rows.joint_rad.begin() + i * n, n, joints.data());
    const double* tip = rows.backbone_m.data() + (i * rows.points + rows.points - 1) * 2;
    Residual r;
    r.measured_gauge_pa = m.gauge_pa;
    r.model_gauge_pa = m.driven_by_volume ? rows.gauge_pa[i] : m.gauge_pa;
    r.gauge_pa = m.hasGauge() ? m.gauge_pa : r.model_gauge_pa;
    r.supplied_volume_m3 = m.supplied_volume_m3;
    r.model_joint_rad.assign(joints.data(), joints.data() + n);
    r.model_avg_rad = n > 1 ? joints.tail(static_cast<Eigen::Index>(n) - 1).mean() : nan;
    r.model_joint1_rad = joints[0];
    r.model_tip_angle_rad = rows.tip_angle_rad[i];
    r.model_tip_x_m = tip[0];
    r.model_tip_y_m = tip[1];
    r.model_chord_angle_rad = chordAngleRad(tip[0], tip[1], r.model_tip_angle_rad);
    r.force_scale_n = force_scale_n;
    measuredInto(parameters, m, r);
    r.model_gauge_at_tip_angle_pa = quantity == CalibrationQuantity::kGaugeAtTipAngle && !r.force_only
                                        ? gaugeOnThePath(model, r.measured_tip_angle_rad, *inverse)
                                        : nan;
    // Defined past the limit point too, where the free finger has no shape.
    r.model_blocked_force_n = m.hasBlockedForce() ? model.blockedTipForceN(m.gauge_pa) : nan;
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace pneumatic_finger
