// finger_calibrate: fit the model's effective parameters to measured joint angles, tip angles or tip positions. See the README, "Tools".
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "pneumatic_finger/calibration/coupon.hpp"
#include "pneumatic_finger/calibration/calibration_run.hpp"
#include "pneumatic_finger/calibration/fit_check.hpp"
#include "pneumatic_finger/calibration/model_selection.hpp"
#include "pneumatic_finger/tools/tool_support.hpp"
#include "pneumatic_finger/core/units.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pf = pneumatic_finger;

namespace {

constexpr const char* kDescription =
    "Fits the model's effective parameters to what was measured: joint angles (the default data, the paper's\n"
    "Table 1), tip angles or tip positions. Prints, per row, the error of every joint, of the joints 2..N average\n"
    "(the paper's measure), of the tip angle (rad) and of the tip position (m), for the fit and leave-one-out (the\n"
    "summary lines add degrees and mm), and writes the calibrated parameter file when --output is given.";

constexpr double kDeg = pf::kDegPerRad;

std::string pad(const std::string& text, int width) {
  return std::string(static_cast<std::size_t>(std::max(0, width - static_cast<int>(text.size()))), ' ') + text;
}

// A table cell: the value, or "-" where the data has nothing to compare.
std::string cell(double v, const char* format, int width) {
  char b[64];
  if (std::isnan(v)) std::snprintf(b, sizeof b, "%*s", width, "-");
  else std::snprintf(b, sizeof b, format, width, v);
  return b;
}

// One table of errors (model - measured), in the data's own units: every joint, the joints 2..N average and the tip
// angle (rad), the tip position (m), and for rows set by volume their volume and the pressure's error (Pa). Also
// returns the largest |error| of each kind in @p worst (joint, average, tip angle, tip position, pressure, the
// pressure's relative error where it was measured above zero, where @p at_bend the pressure at the measured bend, and
// the chord angle where a row measured one).
std::string errorTable(const std::vector<pf::Residual>& rows, int n, bool by_volume, bool at_bend,
                       std::array<double, 9>& worst) {
  // The chord's column only where a row measured one: the reports of other data keep their columns.
  const bool chord = std::any_of(rows.begin(), rows.end(), [](const pf::Residual& r) {
    return !std::isnan(r.measured_chord_angle_rad) && std::isnan(r.measured_tip_x_m);
  });
  const bool force = std::any_of(rows.begin(), rows.end(), [](const pf::Residual& r) {
    return !std::isnan(r.measured_blocked_force_n);
  });
  std::ostringstream t;
  t << "# " << (by_volume ? pad("volume_m3", 11) : "") << pad("gauge_pa", 10);
  for (int k = 1; k <= n; ++k) t << pad("joint_" + std::to_string(k), 9);
  t << pad("avg_2.." + std::to_string(n), 10) << pad("tip_angle", 10) << (chord ? pad("chord", 10) : "")
    << pad("tip_m", 9) << (by_volume ? pad("gauge_err_pa", 13) : "") << (at_bend ? pad("at_bend_err_pa", 15) : "")
    << (force ? pad("force_n", 9) : "") << "\n";
  worst = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  auto keep = [](double& w, double e) {
    if (!std::isnan(e)) w = std::max(w, std::fabs(e));
  };
  for (const pf::Residual& r : rows) {
    t << "# " << (by_volume ? pad(pf::formatNumber("%.4g", r.supplied_volume_m3), 11) : "") << pad(pf::formatMessage(r.gauge_pa), 10);
    for (int k = 0; k < n; ++k) {
      const auto i = static_cast<std::size_t>(k);
      const double e = r.measured_joint_rad.empty() ? NAN : r.model_joint_rad[i] - r.measured_joint_rad[i];
      keep(worst[0], e);
      t << cell(e, "%*.4f", 9);
    }
    keep(worst[1], r.error_rad());
    keep(worst[2], r.tip_angle_error_rad());
    keep(worst[3], r.tip_position_error_m());
    keep(worst[4], r.gauge_error_pa());
    keep(worst[5], r.measured_gauge_pa != 0.0 ? r.gauge_relative_error() : NAN);
    if (at_bend) keep(worst[6], r.gauge_at_tip_angle_error_pa());
    if (chord) keep(worst[7], r.chord_angle_error_rad());
    if (force) keep(worst[8], r.blocked_force_error_n());
    t << cell(r.error_rad(), "%*.4f", 10) << cell(r.tip_angle_error_rad(), "%*.4f", 10)
      << (chord ? cell(r.chord_angle_error_rad(), "%*.4f", 10) : "") << cell(r.tip_position_error_m(), "%*.5f", 9) << (by_volume ? cell(r.gauge_error_pa(), "%*.0f", 13) : "")
      << (at_bend ? cell(r.gauge_at_tip_angle_error_pa(), "%*.0f", 15) : "")
      << (force ? cell(r.blocked_force_error_n(), "%*.4f", 9) : "") << "\n";
  }
  return t.str();
}

// An angle in rad with its degrees beside it, a length in m with its mm: what a reader of the report compares.
std::string angle(double rad) { return pf::formatMessage(rad) + " rad (" + pf::formatNumber("%.3f", rad * kDeg) + " deg)"; }
std::string length(double m) { return pf::formatMessage(m) + " m (" + pf::formatNumber("%.3f", m * 1e3) + " mm)"; }

std::string largest(const std::array<double, 9>& w, int n, bool paper) {
  std::vector<std::string> parts;
  if (w[0] > 0) parts.push_back("joints " + angle(w[0]));
  if (w[1] > 0) {
    parts.push_back("joints 2.." + std::to_string(n) + " average " + angle(w[1]) +
                    (paper ? " (the paper's own model on these data: 0.647 deg)" : ""));
  }
  if (w[2] > 0) parts.push_back("tip angle " + angle(w[2]));
  if (w[7] > 0) parts.push_back("chord angle " + angle(w[7]));
  if (w[8] > 0) parts.push_back("blocked force " + pf::formatNumber("%.4f", w[8]) + " N");
  if (w[3] > 0) parts.push_back("tip position " + length(w[3]));
  if (w[4] > 0) {
    parts.push_back("pressure " + pf::formatNumber("%.0f", w[4]) + " Pa (largest relative " + pf::formatNumber("%.1f", 100.0 * w[5]) + " %)");
  }
  if (w[6] > 0) parts.push_back("pressure at the measured bend " + pf::formatNumber("%.0f", w[6]) + " Pa");
  std::string s;
  for (const std::string& p : parts) s += (s.empty() ? " " : ", ") + p;
  return s;
}

// Each key's standard deviation and the keys' correlations (calibrationUncertainty), and every warning.
std::string uncertaintyLines(const pf::CalibrationRun& run) {
  const pf::CalibrationResult& fit = run.best().fit;
  std::ostringstream t;
  const std::size_t k = fit.keys.size();
  if (std::none_of(fit.uncertainty.begin(), fit.uncertainty.end(), [](double sd) { return std::isfinite(sd); })) {
    t << "\n# uncertainty: none (the warning below says why)";
  } else {
    t << (run.objective == pf::CalibrationObjective::kMinimax
              ? "\n# uncertainty (one standard deviation of the minimax fit, its linearisation refitted to 200 draws "
                "of the data's scatter):"
              : "\n# uncertainty (one standard deviation, from the fit's curvature and the data's scatter):");
    for (std::size_t i = 0; i < k; ++i) {
      t << " " << fit.keys[i] << " +- " << pf::formatNumber("%.3g", fit.uncertainty[i]) << " ("
        // A share of a value of 0 means nothing: the bar alone, in the key's unit.
        << (fit.values[i] != 0.0 ? pf::formatNumber("%.3g", 100.0 * fit.uncertainty[i] / std::fabs(fit.values[i])) + " %)"
                                 : std::string("at a value of 0)"))
        << (i + 1 < k ? "," : "");
    }
  }
  if (k > 1 && std::isfinite(fit.correlation[1])) {
    t << "\n# correlation:";
    for (std::size_t a = 0; a < k; ++a) {
      for (std::size_t b = a + 1; b < k; ++b) {
        t << " " << fit.keys[a] << "/" << fit.keys[b] << " " << pf::formatNumber("%.3f", fit.correlation[a * k + b]);
      }
    }
  }
  for (const std::string& w : run.warnings) t << "\n# warning: " << w;
  return t.str();
}

// The error bar's line: at each calibrated pressure, the tip angle's and the tip position's bar.
std::string errorBarLine(const pf::TipUncertainty& bar, double widening) {
  if (bar.empty()) return "# no error bar written: the data measured neither the tip's angle nor its position\n";
  const std::string widened = widening > 1.0 ? " times " + pf::formatNumber("%.3f", widening) +
                                                   " (auto's choice corrected: the chosen score's ratio)"
                                             : "";
  std::string line = "# error bar written to the parameter file (tip_uncertainty: the largest of fit, leave-one-out" +
                     widened + " and the fit's scatter):";
  for (std::size_t i = 0; i < bar.gauge_pa.size(); ++i) {
    line += " at " + pf::formatMessage(bar.gauge_pa[i]) + " Pa";
    if (!std::isnan(bar.tip_angle_rad[i])) line += " " + pf::formatMessage(bar.tip_angle_rad[i]) + " rad";
    if (!std::isnan(bar.tip_position_m[i])) line += " " + pf::formatMessage(bar.tip_position_m[i]) + " m";
    line += i + 1 < bar.gauge_pa.size() ? ";" : "";
  }
  return line + "\n";
}

// Whether the fit follows its data held out, and the bar it was held to (checkFollows); "" without leave-one-out.
std::string followLine(const pf::CalibrationRun& run) {
  const pf::CalibrationError& e = run.calibration_error;
  if (e.empty()) return "";
  return "# held out, " + (e.follows_data ? std::string("every row") : std::to_string(e.missed_rows) + " row(s) NOT") +
         " within the follow bar, " + pf::formatNumber("%.2f", run.follow_bar_rad * kDeg) + " deg (" +
         pf::followBarReason(run.scatter_rad) + ")\n";
}

// The report: what was fitted to what, the error of the fit and of leave-one-out per row, and the error bar.
// @p paper_data: the package's Table 1, beside which the paper's own model's error is worth printing.
std::string report(const std::string& data_name, bool paper_data, std::size_t rows, const std::string& average_column,
                   const pf::CalibrationRun& run, int n) {
  const pf::CalibrationResult& fit = run.best().fit;
  std::ostringstream table;
  table << "# data: " << data_name << " ("
        << rows << " rows)\n# compared: " << pf::quantityName(run.quantity)
        << (run.by_volume ? " (each row set by its supplied volume; the pressure is the model's output)" : "")
        << (run.quantity == pf::CalibrationQuantity::kOuterAverage
                ? std::string(" (joints 2..") + std::to_string(n) + ", " +
                      (average_column.empty() ? "mean of the measured joints" : "column " + average_column) + ")"
                : "")
        << "; objective: " << pf::objectiveName(run.objective) << "; error = model - measured\n# fitted:";
  for (std::size_t i = 0; i < fit.keys.size(); ++i) table << " " << fit.keys[i] << " = " << pf::formatExact(fit.values[i]);
  table << uncertaintyLines(run);
  std::array<double, 9> worst{}, worst_loo{};
  const bool by_volume = run.by_volume;
  const bool at_bend = run.quantity == pf::CalibrationQuantity::kGaugeAtTipAngle;
  const std::string fit_table = errorTable(fit.residuals, n, by_volume, at_bend, worst);
  const std::string loo_table = errorTable(run.best().leave_one_out, n, by_volume, at_bend, worst_loo);
  table << "\n#\n# error of the fit (angles in rad, tip_m in m)\n" << fit_table
        << "# leave-one-out error: each row predicted by a fit to the others\n" << loo_table
        << "#\n# largest |error|:" << largest(worst, n, paper_data) << "\n# largest leave-one-out |error|:"
        << largest(worst_loo, n, false) << "\n" << followLine(run) << errorBarLine(run.tip_uncertainty, run.leave_one_out_widening);
  return table.str();
}

// The largest and the root-mean-square relative error of the pressure over @p rows measured above zero (%).
std::string relativeSummary(const std::vector<pf::Residual>& rows) {
  double worst = 0.0, sum_sq = 0.0;
  int count = 0;
  for (const pf::Residual& r : rows) {
    if (r.measured_gauge_pa == 0.0) continue;
    const double e = r.gauge_relative_error();
    if (std::isnan(e)) return "no pressure at some row (beyond the limit point)";
    worst = std::max(worst, std::fabs(e));
    sum_sq += e * e;
    ++count;
  }
  return "largest " + pf::formatNumber("%.1f", 100.0 * worst) + " %, rms " + pf::formatNumber("%.1f", 100.0 * std::sqrt(sum_sq / std::max(count, 1))) +
         " %";
}

// The largest and the root-mean-square |term| of @p rows, in rad (m for the tip position); "no shape" where a row
// has none (beyond the limit point).
std::string errorSummary(const std::vector<pf::Residual>& rows, pf::CalibrationQuantity quantity) {
  if (quantity == pf::CalibrationQuantity::kTipAngleAndGauge) {  // each in its own unit
    return "bend " + errorSummary(rows, pf::CalibrationQuantity::kTipAngle) + "; pressure " +
           relativeSummary(rows);
  }
  const bool metres = quantity == pf::CalibrationQuantity::kTipPosition;
  const bool pascals =
      quantity == pf::CalibrationQuantity::kGauge || quantity == pf::CalibrationQuantity::kGaugeAtTipAngle;
  double worst = 0.0, sum_sq = 0.0;
  int count = 0;
  for (const pf::Residual& r : rows) {
    for (double e : r.terms(quantity)) {
      if (std::isnan(e)) return "no shape at some row (beyond the limit point)";
      worst = std::max(worst, std::fabs(e));
      sum_sq += e * e;
      ++count;
    }
  }
  const double rms = std::sqrt(sum_sq / std::max(count, 1));
  if (pascals) return "largest " + pf::formatNumber("%.0f", worst) + " Pa, rms " + pf::formatNumber("%.0f", rms) + " Pa";
  return metres ? "largest " + length(worst) + ", rms " + length(rms) : "largest " + angle(worst) + ", rms " + angle(rms);
}

// --wall-law with more than one law: each law's keys, fit and leave-one-out side by side, and the choice.
std::string lawComparison(const pf::CalibrationRun& run) {
  std::ostringstream t;
  t << "# wall laws compared (" << pf::quantityName(run.quantity)
    << "; the law with the smaller leave-one-out error is kept):\n";
  for (std::size_t i = 0; i < run.fits.size(); ++i) {
    const pf::WallLawFit& f = run.fits[i];
    t << "#   " << pf::wallLawName(f.law) << ": " << f.fit.keys.size() << " fitted (";
    for (std::size_t k = 0; k < f.fit.keys.size(); ++k) t << (k ? ", " : "") << f.fit.keys[k];
    t << "); fit " << errorSummary(f.fit.residuals, run.quantity) << "; leave-one-out "
      << errorSummary(f.leave_one_out, run.quantity) << (i == run.chosen ? "  <- chosen" : "") << "\n";
    if (!f.note.empty()) t << "#     (" << pf::wallLawName(f.law) << ": " << f.note << ")\n";
  }
  return t.str() + "#\n";
}

// The options of a fit to an actuator's measurements (--data and the rest).
struct DataOptions {
  std::vector<std::string> data_paths;
  std::string objective_name = "minimax", average_column, fit_keys, compare, wall_law, drive;
};

void addDataOptions(CLI::App& app, DataOptions& o) {
  pf::addRepeatedOption(app, "--data", o.data_paths,
                        "measured CSV: gauge_pa and/or supplied_volume_m3, and any of joint_1_rad..joint_N_rad, "
                        "tip_angle_rad, chord_angle_rad (base to tip, as one marker on a video gives it), "
                        "tip_x_m,tip_y_m (the tip in the finger's frame), blocked_tip_force_n (the finger held "
                        "straight; a row may hold it alone); repeat it for several files of one actuator (its bends "
                        "and its blocked force); default: the package's data/sierra2022_table1.csv", "CSV");
  app.add_option("--drive", o.drive,
                 "what set each row: pressure (gauge_pa) or volume (supplied_volume_m3: a syringe pump or a "
                 "displacement-controlled cylinder; the model's pressure is then compared with gauge_pa by "
                 "--compare gauge_pa, and dead_volume_m3 can be fitted); default: pressure where the file has "
                 "gauge_pa, else volume");
  app.add_option("--compare", o.compare,
                 "what the fit compares: joints (with base_wall_share: the chamber keys to the joints 2..N average, "
                 "then base_wall_share to joint 1), average (of joints 2..N, the paper's measure), joint_1, tip_angle, "
                 "tip_position, chord_angle (base to tip), gauge_pa (the pressure at each row's volume, with --drive volume) or "
                 "tip_angle+gauge_pa (both, with --drive volume: the tip angle's error in rad and the pressure's "
                 "relative error, 1 deg of bend weighing as 1.75 % of the pressure) or gauge_at_tip_angle (the "
                 "pressure that holds each measured bend, against the measured, in Pa: continuous through a snap); "
                 "default: joints if the file has them, else tip_position, else tip_angle (chord_angle where only the "
                 "chord was measured), or gauge_at_tip_angle where the tip angle leaps (by a quarter of its range within 5 % of the pressures': a snap); with --drive "
                 "volume and gauge_pa measured, tip_angle+gauge_pa instead of the bend alone");
  app.add_option("--fit", o.fit_keys,
                 "parameter keys to fit (any number, each once), comma-separated; default: shear_modulus_pa,chamber_gap_m and, "
                 "when every joint is compared, base_wall_share (joint_1: base_wall_share alone)");
  app.add_option("--objective", o.objective_name,
                 "minimax, least_squares or huber (least squares with Huber's robust loss: an outlying row does not "
                 "pull the fit)")->capture_default_str();
  app.add_option("--average-column", o.average_column,
                 "take the joints 2..N average from this column (e.g. paper_avg_rad) instead of the joints; implies "
                 "--compare average");
  app.add_option("--wall-law", o.wall_law,
                 "auto, paper, membrane or thick; default: the parameter file's wall_law. auto without --fit chooses "
                 "the law, the keys and the comparison: for each law, forward selection from its default keys "
                 "(adding wall_locking_jm, wall_bulge_share, and by volume dead_volume_m3 and chamber_growth_ratio); "
                 "then, for the chosen membrane or thick law only, drawing/roof_thickness_m where the drawing leaves "
                 "the roof to its default. A key is kept where the rows held out (their bends, and the pressure or "
                 "the blocked force where they are data) are clearly better (docs/CALIBRATE.md, \"What auto "
                 "chooses\"). auto with --fit fits those keys under each law and keeps the best leave-one-out. Without --fit a "
                 "named law fits shear_modulus_pa,chamber_gap_m, and base_wall_share where every joint is compared, else "
                 "wall_locking_jm under the membrane law (joint_1: base_wall_share alone)");
}

std::ofstream openOutput(const std::string& output) {
  std::ofstream out(output);
  if (!out) throw pf::ParameterError("cannot write '" + output + "'");
  return out;
}

// The fit to an actuator's measurements: the report, and the calibrated file when @p output is given.
int calibrateOnData(const pf::ParameterOptions& parameters, DataOptions o, const std::string& output) {
  const bool default_data = o.data_paths.empty();
  if (default_data) o.data_paths = {pf::packageShareDirectory() + "/data/sierra2022_table1.csv"};
  std::string data_name;
  for (const std::string& p : o.data_paths) data_name += (data_name.empty() ? "" : " + ") + p;
  pf::CalibrationRequest request;
  request.wall_law = o.wall_law;
  request.keys = pf::splitFields(o.fit_keys);
  request.objective = o.objective_name;
  request.compare = o.compare;
  request.average_column = o.average_column;
  request.drive = o.drive;
  request.progress = pf::CalibrationProgressPrinter(std::cerr, "finger_calibrate");  // quiet for the first 2 s
  if (!o.wall_law.empty()) pf::parseWallLawChoice(o.wall_law);  // refused before the data, whose name it is not
  const pf::FingerParameters base = pf::calibrationBase(parameters.loadRaw(), o.wall_law);
  const pf::MeasurementSet data = pf::readMeasurementSets(o.data_paths, 1, o.average_column);
  pf::CalibrationRun run;
  try {
    run = pf::runCalibration(base, data, request);
  } catch (const pf::ParameterError& e) {
    throw pf::ParameterError(data_name + ": " + e.what());
  }
  const std::string choice = !run.candidates.empty()
                                 ? pf::candidatesTable(run.candidates, run.chosen_candidate)
                                 : run.fits.size() > 1 ? lawComparison(run) : std::string();
  const std::string table = choice +
                            report(default_data ? "the package's data/sierra2022_table1.csv" : data_name,
                                   default_data, data.rows.size(), o.average_column, run, base.chamber_count);
  std::cout << table;
  if (output.empty()) return 0;
  // What this file is, and nothing it is not: the base parameters with the fitted keys replaced, and the fit's
  // report as comments (docs/CALIBRATE.md reads it line by line).
  openOutput(output) << "# A calibrated actuator, written by `finger_calibrate --output`: the base parameters with the fitted\n"
                     << "# keys replaced, and the fit's report (docs/CALIBRATE.md). Load it with finger.launch config:=FILE.\n"
                     << table << "\n"
                     << pf::calibratedParameterYaml(run, parameters.loadRange());
  return 0;
}

// --coupon: the wall law's material (shear_modulus_pa, wall_locking_jm) from a coupon test of the elastomer, nothing
// fitted to an actuator; the file written is the base file with those two keys replaced.
int fitElastomer(const pf::ParameterOptions& parameters, const std::string& coupon_path, const std::string& law,
                 const std::string& output) {
  const bool gent = pf::parseCouponLaw(law);
  const pf::RawParameterMap raw = parameters.loadRaw();
  const pf::CouponTest test = pf::loadCouponCsv(coupon_path);
  const pf::CouponFit fit = pf::fitCoupon(test, gent);
  const std::string text = pf::couponFitReport(fit, test);
  const std::string file = pf::couponParameterYaml(raw, fit, parameters.loadRange());  // refuses the paper law
  std::cout << text;
  if (output.empty()) return 0;
  openOutput(output) << "# An elastomer from its coupon test, written by `finger_calibrate --coupon --output`: the base\n"
                     << "# parameters with the wall law's material replaced (docs/CALIBRATE.md); nothing is fitted to an\n"
                     << "# actuator.\n" << text << "\n" << file;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app(kDescription, "finger_calibrate");
  pf::ParameterOptions parameters;
  parameters.addTo(app);
  DataOptions data;
  addDataOptions(app, data);
  std::string output, coupon, coupon_law = "gent";
  app.add_option("--output", output, "write the calibrated parameter file (YAML) here");
  app.add_option("--coupon", coupon,
                 "instead of an actuator's data: a uniaxial coupon test of the elastomer (CSV: engineering_strain, "
                 "nominal_stress_pa in Pa); fits the wall law's shear_modulus_pa and wall_locking_jm, with their "
                 "uncertainty, into the base file (membrane or thick law)");
  app.add_option("--coupon-law", coupon_law, "the elastomer's law for --coupon: gent or neo-hookean")
      ->capture_default_str();
  return pf::runTool("finger_calibrate", app, argc, argv, [&] {
    if (coupon.empty()) return calibrateOnData(parameters, data, output);
    if (!data.data_paths.empty()) {
      throw pf::ParameterError("give --coupon or --data, not both: the coupon fits the elastomer alone; calibrate "
                               "the actuator on the file --coupon --output writes");
    }
    return fitElastomer(parameters, coupon, coupon_law, output);
  });
}
