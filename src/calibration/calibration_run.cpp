// One calibration, as finger_calibrate and pf.calibrate run it (calibration_run.hpp).
#include "pneumatic_finger/calibration/calibration_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include <string>
#include <vector>

#include "pneumatic_finger/calibration/fit_check.hpp"
#include "pneumatic_finger/calibration/model_selection.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pneumatic_finger {

FingerParameters calibrationBase(RawParameterMap raw, const std::string& wall_law) {
  // The membrane's and the thick wall's geometry rules are the same (b may exceed L).
  const bool membrane_considered = wall_law == "auto" || wall_law == wallLawName(WallLaw::kMembrane) ||
                                   wall_law == wallLawName(WallLaw::kThick);
  // Each law's fit sets its own wall_law (calibrateWallLaws), so the file's is only the validation's.
  if (membrane_considered) {
    const ParameterSpec& spec = *findParameterSpec("wall_law");
    RawParameterValue law;
    law.values.push_back(parseParameterText(spec, wallLawName(WallLaw::kMembrane)));
    raw["wall_law"] = law;
  }
  return FingerParameters::fromRaw(raw);
}

namespace {

// Rows filled by volume with their pressure measured compare both by default: the bend alone leaves the modulus free
// (an incompressible fill sets the shape by the volume, the modulus only the pressure), so a default of the bend alone
// would refuse the usual fit (mu among the keys) that the measured pressure makes possible.
CalibrationQuantity quantityFor(const CalibrationRequest& request, const std::vector<Measurement>& rows,
                                bool by_volume) {
  if (!request.compare.empty()) return parseQuantity(request.compare);
  if (!request.average_column.empty()) return CalibrationQuantity::kOuterAverage;
  const CalibrationQuantity bend = defaultQuantity(rows);
  const bool bend_alone = bend == CalibrationQuantity::kTipAngle || bend == CalibrationQuantity::kGaugeAtTipAngle;
  return by_volume && bend_alone && rows.front().hasGauge() ? CalibrationQuantity::kTipAngleAndGauge : bend;
}

// The comparisons auto tries: the one asked for; else the data's default and, where that compares the pressure at
// each bend (a tip angle that leaps), the bend at its pressure too, which the yardstick then judges alike.
std::vector<CalibrationQuantity> comparisonsFor(const CalibrationRequest& request, CalibrationQuantity quantity) {
  if (!request.compare.empty() || quantity != CalibrationQuantity::kGaugeAtTipAngle) return {quantity};
  return {quantity, CalibrationQuantity::kTipAngle};
}

// One law without leave-one-out: the fit alone (Python's quick fit).
WallLawFit fitOnly(const FingerParameters& base, const std::vector<std::string>& keys, const MeasurementSet& data,
                   CalibrationObjective objective, CalibrationQuantity quantity, const CalibrationProgress& progress) {
  WallLawFit f;
  f.law = base.wall_law;
  f.fit = calibrate(base, keys.empty() ? defaultFitKeys(quantity, base.wall_law) : keys, data.rows, objective,
                    quantity,
                    progress ? CalibrationProgress([&](const std::string& s) { progress("the fit: " + s); })
                             : CalibrationProgress());
  return f;
}

// Driven by volume with no gas in the drive, neither given nor fitted: the supplied volume is all the chambers'
// growth, as an incompressible fluid makes it. Where the drive pushes air, its gas takes a share that grows with the
// pressure, and a fit without it is far off (the ribbed segment by volume, auto: 40 deg; docs/CALIBRATE.md): said,
// with the way to fit it.
std::string gasWarning(const FingerParameters& base, const std::vector<std::string>& keys, bool has_gauge) {
  if (base.dead_volume_m3 != 0.0 || std::find(keys.begin(), keys.end(), "dead_volume_m3") != keys.end()) return {};
  return std::string("driven by volume with dead_volume_m3 = 0: each row's supplied volume is taken as the chambers' "
                     "growth alone, as an incompressible fluid gives it. If the drive pushes air, its gas takes a "
                     "share: ") +
         (has_gauge ? "fit it first (--drive volume --compare gauge_pa --fit dead_volume_m3) or give it"
                    : "give it") +
         " (--set dead_volume_m3=V; docs/CALIBRATE.md, \"A finger filled by volume\")";
}

}  // namespace

CalibrationRun runCalibration(const FingerParameters& base, const MeasurementSet& data,
                              const CalibrationRequest& request) {
  CalibrationRun run;
  run.objective = parseObjective(request.objective);
  MeasurementSet driven = data;
  const bool has_gauge = !data.rows.empty() && data.rows.front().hasGauge();
  run.by_volume = request.drive.empty() ? !has_gauge : parseDrive(request.drive);
  run.quantity = quantityFor(request, data.rows, run.by_volume);
  driveByVolume(driven.rows, run.by_volume);
  setForceScale(driven.rows);  // one scale for the forces, whichever rows a fold leaves out
  checkMeasurementsPlausible(base, driven.rows);  // before any law's fit, so that its message names no law
  const std::vector<WallLaw> laws =
      request.wall_law.empty() ? std::vector<WallLaw>{base.wall_law} : parseWallLawChoice(request.wall_law);
  if (laws.size() > 1 && request.keys.empty()) {  // auto chooses the keys and the comparison too
    ModelSelection selection = selectModel(base, laws, comparisonsFor(request, run.quantity), driven.rows,
                                           run.objective, run.by_volume, request.progress);
    run.quantity = selection.chosen.quantity;
    run.fits = {std::move(selection.chosen)};
    run.candidates = std::move(selection.tried);
    run.chosen_candidate = selection.chosen_index;
    // The chosen candidate's held-out errors are the best of several: widened by the choice's optimism.
    const double score = run.candidates[run.chosen_candidate].held_out.score;
    run.leave_one_out_widening = score > 0.0 ? correctedScore(run.candidates, run.chosen_candidate) / score : 1.0;
    run.tip_uncertainty = tipUncertainty(run.best().fit.residuals, run.best().leave_one_out,
                                         run.best().fit.keys.size(), run.leave_one_out_widening);
  } else if (laws.size() == 1 && !request.leave_one_out) {
    FingerParameters one = base;
    one.wall_law = laws[0];
    run.fits.push_back(fitOnly(one, request.keys, driven, run.objective, run.quantity, request.progress));
  } else {
    run.fits = calibrateWallLaws(base, laws, request.keys, driven.rows, run.objective, run.quantity, request.progress);
    run.chosen = chosenWallLaw(run.fits);
    run.tip_uncertainty =
        tipUncertainty(run.best().fit.residuals, run.best().leave_one_out, run.best().fit.keys.size());
  }
  run.warnings = data.notes;
  if (run.by_volume) {
    const std::string gas = gasWarning(base, run.best().fit.keys, has_gauge);
    if (!gas.empty()) run.warnings.push_back(gas);
  }
  for (const std::string& w : run.best().fit.warnings) run.warnings.push_back(w);
  if (!run.best().leave_one_out.empty()) {  // what a row the fit has not seen gets: does it follow the data?
    FitCheck check = checkFollows(run.best().leave_one_out, driven.rows, run.quantity, run.by_volume,
                                  !run.candidates.empty());
    run.calibration_error = check.error;
    run.follow_bar_rad = check.bar_rad;
    run.scatter_rad = check.scatter_rad;
    if (!check.warning.empty()) run.warnings.push_back(check.warning);
  }
  if (!run.tip_uncertainty.empty()) {
    const std::string unpredicted = unpredictedRowsWarning(run.best().fit.residuals, run.best().leave_one_out);
    if (!unpredicted.empty()) run.warnings.push_back(unpredicted);
  }
  return run;
}

CalibrationProgressPrinter::CalibrationProgressPrinter(std::ostream& out, std::string who, double quiet_s)
    : out_(&out), who_(std::move(who)), quiet_s_(quiet_s), start_(std::chrono::steady_clock::now()), last_(start_) {}

void CalibrationProgressPrinter::operator()(const std::string& step) {
  const auto now = std::chrono::steady_clock::now();
  const double since_start = std::chrono::duration<double>(now - start_).count();
  const double since_last = std::chrono::duration<double>(now - last_).count();
  if (since_start < quiet_s_ || (last_ != start_ && since_last < quiet_s_)) return;
  last_ = now;
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.1f", since_start);
  *out_ << who_ << ": " << seconds << " s: " << step << std::endl;
}

PressureRange calibratedRange(const CalibrationRun& run, const PressureRange& file_range) {
  double top_pa = 0.0;
  for (const Residual& r : run.best().fit.residuals) {
    if (std::isfinite(r.gauge_pa)) top_pa = std::max(top_pa, r.gauge_pa);
  }
  PressureRange range = file_range;
  if (!(top_pa > 0.0)) return range;  // no pressure seen: the file's range stands
  range.validated_max_gauge_pa = top_pa;
  range.max_gauge_pa = std::max(range.max_gauge_pa, top_pa);
  return range;
}

std::string calibratedParameterYaml(const CalibrationRun& run, const PressureRange& file_range) {
  // No bar where the data measured neither the tip's angle nor its position (chord angles alone): none is written.
  const std::string bar = run.tip_uncertainty.empty()
                              ? "# No tip_uncertainty: the data measured neither the tip's angle nor its position.\n"
                              : tipUncertaintyToYaml(run.tip_uncertainty);
  const std::string record = calibrationErrorToYaml(run.calibration_error);
  return parametersToYaml(run.best().fit.parameters) + "\n" + rangeToYaml(calibratedRange(run, file_range)) + "\n" +
         bar + (record.empty() ? "" : "\n" + record);
}

}  // namespace pneumatic_finger
