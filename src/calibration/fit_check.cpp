// Whether a calibration follows its data (fit_check.hpp): the missed rows, said plainly, and the file's record.
#include "pneumatic_finger/calibration/fit_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "pneumatic_finger/calibration/model_selection.hpp"
#include "pneumatic_finger/core/chord_angle.hpp"

namespace pneumatic_finger {

namespace {

// A row's measured bend for the scatter: every joint's sum, the tip angle, the chord (or its tip position's); NaN.
double measuredBend(const Measurement& m) {
  if (m.hasJoints()) {
    double sum = 0.0;
    for (double q : m.joint_rad) sum += q;
    return sum;
  }
  if (m.hasTipAngle()) return m.tip_angle_rad;
  if (m.hasChordAngle()) return m.chord_angle_rad;
  if (m.hasTipPosition()) return chordAngleRad(m.tip_x_m, m.tip_y_m, std::numeric_limits<double>::quiet_NaN());
  return std::numeric_limits<double>::quiet_NaN();
}

// A held-out row's bend error (rad): its largest joint's, else its tip angle's, else its chord's; NaN: no shape;
// @p measured false where the row measured no bend.
double bendError(const Residual& r, bool& measured) {
  const std::vector<double> bends = heldOutBendErrors(r);  // the yardstick's bends
  measured = !bends.empty();
  double worst = 0.0;
  for (double e : bends) {
    if (std::isnan(e)) return e;
    if (std::fabs(e) > std::fabs(worst)) worst = e;
  }
  return worst;
}

// What to try, for the rows missed: the words depend on what the data and the run were.
std::string whatToTry(const std::vector<Residual>& held_out, int unshaped, bool pressure_missed, bool by_volume,
                      bool auto_chosen) {
  std::vector<std::string> hints;
  if (unshaped > 0) {
    hints.push_back("the model has no shape at " + std::to_string(unshaped) + " row(s), past its limit point: drive it "
                    "by volume (--drive volume), or fit Gent's lock (wall_locking_jm), which stiffens the wall again");
  }
  if (!auto_chosen) hints.push_back("let --wall-law auto choose the law and the keys (no --fit)");
  const bool tip_column = std::any_of(held_out.begin(), held_out.end(), [](const Residual& r) {
    return r.measured_joint_rad.empty() && !std::isnan(r.measured_tip_angle_rad);
  });
  if (tip_column) {
    hints.push_back("if your angle is the line from the base to the tip (one marker tracked on a video), it is a "
                    "chord: name the column chord_angle_rad");
  }
  if (by_volume && pressure_missed) {
    hints.push_back("fit the drive's gas (dead_volume_m3) and the skin's share (chamber_growth_ratio)");
  }
  hints.push_back("measure what the model cannot infer: every joint, or the drawing's roof and body width "
                  "(docs/DRAWING.md)");
  std::string s;
  for (std::size_t i = 0; i < hints.size(); ++i) s += (i ? "; " : "") + hints[i];
  return s;
}

}  // namespace

double bendScatterRad(const std::vector<Measurement>& data) {
  std::vector<std::pair<double, double>> rows;  // (pressure, bend) of the rows set by their pressure
  for (const Measurement& m : data) {
    const double bend = measuredBend(m);
    if (!m.driven_by_volume && m.hasGauge() && !std::isnan(bend)) rows.emplace_back(m.gauge_pa, bend);
  }
  std::sort(rows.begin(), rows.end());
  if (rows.size() < kScatterRows) return 0.0;
  std::vector<double> departures;
  for (std::size_t i = 1; i + 1 < rows.size(); ++i) {
    const double span = rows[i + 1].first - rows[i - 1].first;
    if (!(span > 0.0)) continue;
    const double w = (rows[i + 1].first - rows[i].first) / span;  // the left neighbour's weight
    const double line = w * rows[i - 1].second + (1.0 - w) * rows[i + 1].second;
    departures.push_back(std::fabs(rows[i].second - line) / std::sqrt(1.0 + w * w + (1.0 - w) * (1.0 - w)));
  }
  if (departures.empty()) return 0.0;
  const auto middle = departures.begin() + static_cast<long>(departures.size() / 2);
  std::nth_element(departures.begin(), middle, departures.end());
  return 1.4826 * *middle;
}

std::string followBarReason(double scatter_rad) {
  const std::string floor = formatNumber("%.0f", kFollowFloorRad * 180.0 / M_PI) + " deg";
  if (!(scatter_rad > 0.0)) {
    return floor + ": the data's own scatter is measured on " + std::to_string(kScatterRows) +
           " rows or more set by their pressure, each with a bend, and these have fewer";
  }
  return "the larger of " + floor + " and " + formatNumber("%.0f", kFollowScatters) + " times the data's own scatter, " +
         formatNumber("%.2f", scatter_rad * 180.0 / M_PI) + " deg";
}

FitCheck checkFollows(const std::vector<Residual>& held_out, const std::vector<Measurement>& data,
                      CalibrationQuantity quantity, bool by_volume, bool auto_chosen) {
  const double scatter_rad = bendScatterRad(data);
  const double bar_rad = std::max(kFollowFloorRad, kFollowScatters * scatter_rad);
  FitCheck check;
  check.bar_rad = bar_rad;
  check.scatter_rad = scatter_rad;
  CalibrationError& e = check.error;
  double sum_sq = 0.0, largest = -1.0;
  int bends = 0, unshaped = 0;
  bool pressure_missed = false;
  std::vector<std::pair<double, std::string>> missed;  // (how far, the words), to name the worst first
  for (const Residual& r : held_out) {
    bool measured = false;
    double bend = bendError(r, measured);
    const bool shapeless = measured && std::isnan(bend);
    if (shapeless) bend = kUnshapedBendRad, ++unshaped;
    if (measured) {
      sum_sq += bend * bend, ++bends;
      if (std::fabs(bend) > largest) largest = std::fabs(bend), e.largest_at_gauge_pa = r.gauge_pa;
    }
    const double p = by_volume && r.measured_gauge_pa > 0.0 ? r.gauge_relative_error() : 0.0;
    const bool bend_missed = measured && (shapeless || std::fabs(bend) > bar_rad);
    const bool p_missed = !std::isnan(p) && std::fabs(p) > kFollowPressure;
    if (!bend_missed && !p_missed) continue;
    pressure_missed = pressure_missed || p_missed;
    ++e.missed_rows;
    missed.emplace_back(std::max(bend_missed ? std::fabs(bend) / bar_rad : 0.0, p_missed ? std::fabs(p) / kFollowPressure : 0.0),
                        formatMessage(r.gauge_pa) + " Pa (" +
                            (shapeless ? std::string("no shape") : bend_missed ? formatNumber("%+.1f deg", bend * 180.0 / M_PI) : "") +
                            (p_missed ? std::string(bend_missed ? ", " : "") + "pressure " + formatNumber("%+.0f %%", 100.0 * p) : "") +
                            ")");
  }
  std::stable_sort(missed.begin(), missed.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::string rows;
  for (std::size_t i = 0; i < missed.size() && i < 8; ++i) rows += (i ? ", " : "") + missed[i].second;
  if (bends == 0) return FitCheck{};  // no bend measured: nothing to record
  e.compared = quantityName(quantity);
  e.held_out_rms_rad = std::sqrt(sum_sq / bends);
  e.held_out_largest_rad = largest;
  e.follows_data = e.missed_rows == 0;
  if (e.follows_data) return check;
  check.warning = "the fit does not follow its data: " + std::to_string(e.missed_rows) + " of " +
                  std::to_string(held_out.size()) + " rows are missed when held out by more than " +
                  formatNumber("%.1f", bar_rad * 180.0 / M_PI) + " deg (" + followBarReason(scatter_rad) + ")" +
                  (by_volume ? " or their pressure by more than " + formatNumber("%.0f %%", 100.0 * kFollowPressure) : "") +
                  "; the worst at " + rows + (e.missed_rows > 8 ? " and " + std::to_string(e.missed_rows - 8) + " more" : "") +
                  "; try: " +
                  whatToTry(held_out, unshaped, pressure_missed, by_volume, auto_chosen);
  return check;
}

}  // namespace pneumatic_finger
