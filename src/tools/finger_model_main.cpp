// finger_model: the model from the command line, as CSV (one row per pressure). See the README, "Tools".
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "pneumatic_finger/core/chord_angle.hpp"
#include "pneumatic_finger/core/drawing.hpp"
#include "pneumatic_finger/core/evaluation_report.hpp"
#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/pressure_range.hpp"
#include "pneumatic_finger/core/regulator.hpp"
#include "pneumatic_finger/core/self_contact.hpp"
#include "pneumatic_finger/core/units.hpp"
#include "pneumatic_finger/tools/tool_support.hpp"
#include "model_listings.hpp"
#include "row_warnings.hpp"

namespace pf = pneumatic_finger;
using pneumatic_finger_tools::Listings;
using pneumatic_finger_tools::RowWarnings;

namespace {

constexpr const char* kDescription =
    "The finger model from the command line. Prints CSV, one row per pressure:\n"
    "gauge_pa,stretch,bulge_m,half_angle_rad,joint_1_rad..joint_N_rad,tip_x_m,tip_y_m,supplied_volume_m3\n"
    "(stretch, bulge and half angle of chamber 1; the volume the supply has pushed in, docs/MODEL.md Volume; 17\n"
    "significant digits). Exit 2 on bad input.\n"
    "Volume as the input (--supplied-volume-m3 V, --sweep-volume-m3): the same columns, gauge_pa the pressure the\n"
    "volume makes; under the membrane law the volume sets the shape past the limit point too.\n"
    "Time mode (--flow-lpm Q --duration-s T --step-s DT): a constant flow fills one finger; each row starts with\n"
    "time_s, at 0, DT, .., T, the gauge pressure P_o Q t / V_o (eq 4, ideal spring; V_o = sum L d e).\n"
    "--blocked-tip-force adds blocked_tip_force_n: the tip force (N) of the finger held straight by a plate at its\n"
    "tip (docs/MODEL.md, Force).";

// FROM:TO:COUNT of option @p option (--sweep-pa, --sweep-volume-m3): COUNT evenly spaced values.
std::vector<double> parseSweep(const std::string& option, const std::string& text) {
  const std::vector<std::string> f = pf::splitFields(text, ':');
  if (f.size() != 3) throw pf::ParameterError(option + " expects FROM:TO:COUNT, got '" + text + "'");
  const double a = pf::parseFiniteOption(option + " FROM", f[0]);
  const double b = pf::parseFiniteOption(option + " TO", f[1]);
  const double n = pf::parseFiniteOption(option + " COUNT", f[2]);
  if (n < 1 || n > 1e7 || n != static_cast<double>(static_cast<long>(n))) {
    throw pf::ParameterError(option + " COUNT = " + f[2] + " must be a whole number in [1, 10000000]");
  }
  std::vector<double> out;
  const long k = static_cast<long>(n);
  for (long i = 0; i < k; ++i) out.push_back(k == 1 ? a : a + (b - a) * static_cast<double>(i) / (k - 1));
  return out;
}

// What the rows hold besides the shape: a time first (the time mode), the finger closing on an obstacle, the blocked
// tip force last.
struct CsvColumns {
  pf::PressureRange range;  // the model's range, applied to every row as finger_node applies it
  bool start_far = false;   // --start-branch far: the first row starts from the walls' far branch
  const pf::Obstacle* obstacle = nullptr;
  std::vector<double> times;
  bool blocked_tip_force = false;
  bool status = false;  // --status: each row's outcome and flags, as finger_state and Python's evaluate carry them
  bool chord_angle = false;  // --chord-angle: the angle of the line base to tip, as finger_state carries it
};

// The options that add columns or set the rows' range.
void addColumnOptions(CLI::App& app, CsvColumns& columns, std::string& max_gauge) {
  app.add_option("--max-gauge-pa", max_gauge,
                 "top of the model's range (Pa; default the parameter file's max_gauge_pa, else 294199.5 = 3 kg/cm2): "
                 "a pressure above it, or a volume that makes more, is clamped to it, with a warning, as finger_node's "
                 "~max_gauge_pa does");
  app.add_flag("--blocked-tip-force", columns.blocked_tip_force,
               "add blocked_tip_force_n: the tip force (N) of the finger held straight by a plate at its tip");
  app.add_flag("--chord-angle", columns.chord_angle, "add chord_angle_rad after tip_y_m: from the finger's rest "
               "direction to the line from its base to its tip (rad), what one marker on a video measures");
  app.add_flag("--status", columns.status,
               "add status and status_flags: each row's outcome code and the flags that hold besides it (the codes of "
               "finger_state and of Python's evaluate: docs/LIBRARY.md, Status)");
}

// The header row: the time first (time mode), the shape, the supplied volume, the blocked tip force last.
void printHeader(std::ostream& out, int chamber_count, bool time, const CsvColumns& columns) {
  if (time) out << "time_s,";
  out << "gauge_pa,stretch,bulge_m,half_angle_rad";
  for (int j = 1; j <= chamber_count; ++j) out << ",joint_" << j << "_rad";
  out << ",tip_x_m,tip_y_m" << (columns.chord_angle ? ",chord_angle_rad" : "") << ",supplied_volume_m3"
      << (columns.blocked_tip_force ? ",blocked_tip_force_n" : "") << (columns.status ? ",status,status_flags\n" : "\n");
}

// The fields of a row with no shape, after its first (the pressure, or nan): the shape's and the supplied volume's.
int shapelessFields(int chamber_count, const CsvColumns& columns) {
  return chamber_count + 5 + (columns.chord_angle ? 1 : 0);
}

// A row by volume with no shape: nan for the pressure and the shape, then its volume @p v.
void printShapelessVolumeRow(std::ostream& out, int chamber_count, const CsvColumns& columns, double v) {
  out << "nan";
  for (int j = 0; j < shapelessFields(chamber_count, columns); ++j) out << ",nan";
  out << ',' << pf::formatExact(v);
}

// A row's outcome by the core's one rule (evaluation_report.hpp), as its codes.
pf::EvaluationReport rowReport(const pf::FingerState& s, const pf::RangeCheck& range) {
  const bool shaped = s.status != pf::EvaluationStatus::kNotFinite && s.status != pf::EvaluationStatus::kSolverFailure &&
                      s.status != pf::EvaluationStatus::kBeyondLimitPoint && s.status != pf::EvaluationStatus::kVacuum;
  return pf::reportEvaluation(s.status, range, shaped && pf::backboneMeetsItself(s.backbone_m, s.joint_angle_rad.data()));
}

void printReport(std::ostream& out, const pf::EvaluationReport& report) {
  out << ',' << static_cast<int>(report.status) << ',' << static_cast<int>(report.flags);
}

// The shape's columns of a state, gauge_pa to tip_y_m (and the chord angle, the tip's direction the joints' sum),
// with joints @p q (held ones included, on an obstacle) and tip @p tip.
void printShape(std::ostream& out, const pf::FingerState& s, const Eigen::VectorXd& q, const Eigen::Vector2d& tip,
                bool chord_angle) {
  out << pf::formatExact(s.gauge_pa) << ',' << pf::formatExact(s.stretch[0]) << ',' << pf::formatExact(s.bulge_m[0])
      << ',' << pf::formatExact(s.half_angle_rad[0]);
  for (Eigen::Index j = 0; j < q.size(); ++j) out << ',' << pf::formatExact(q[j]);
  out << ',' << pf::formatExact(tip.x()) << ',' << pf::formatExact(tip.y());
  if (chord_angle) out << ',' << pf::formatExact(pf::chordAngleRad(tip.x(), tip.y(), q.sum()));
}

void printCsv(const pf::FingerModel& model, pf::FingerWorkspace& ws, const std::vector<double>& pressures,
              const CsvColumns& columns) {
  const pf::ContactSolver contact(model);
  const pf::Obstacle* obstacle = columns.obstacle;
  const std::vector<double>& times = columns.times;
  bool warned_overlap = false;
  const int n = model.chamberCount();
  std::ostringstream out;
  printHeader(out, n, !times.empty(), columns);
  // Computed only when asked for (it costs a wall solve): the held finger's force, whatever the free shape's status.
  auto end_row = [&](double p, const pf::FingerState& s, const pf::RangeCheck& range) {
    if (columns.blocked_tip_force) out << ',' << pf::formatExact(model.blockedTipForceN(p));
    if (columns.status) printReport(out, rowReport(s, range));
    out << '\n';
  };
  RowWarnings warn;
  model.startBranch(ws, columns.start_far);
  for (std::size_t row = 0; row < pressures.size(); ++row) {
    // The range rule of every interface: the row is the finger at the pressure the model was given.
    const pf::RangeCheck range = pf::checkGaugeRange(pressures[row], columns.range);
    const double p = range.gauge_pa;
    if (!times.empty()) out << pf::formatShortest(times[row]) << ',';
    const pf::FingerState& s = model.evaluate(p, ws);
    warn.note(model, s, range, pressures[row], columns.range);
    if (s.status == pf::EvaluationStatus::kSolverFailure || s.status == pf::EvaluationStatus::kBeyondLimitPoint) {
      // The model kept its previous state; printing it would put a wrong shape on this row.
      out << pf::formatExact(p);
      for (int j = 0; j <= shapelessFields(n, columns); ++j) out << ",nan";
      end_row(p, s, range);
      continue;
    }
    Eigen::VectorXd q = s.joint_angle_rad;
    Eigen::Vector2d tip = s.tip();
    double volume_m3 = model.suppliedVolumeOf(s);
    if (obstacle) {
      // The finger closing on the obstacle: joints held where the backbone touched it (docs/GRASP.md).
      const pf::ContactState c = contact.solve(p, *obstacle);
      if (c.status == pf::ContactState::Status::kOverlapsAtRest && !warned_overlap) {
        std::cerr << "finger_model: warning: the obstacle overlaps the straight finger; printing the free finger\n";
        warned_overlap = true;
      }
      if (c.status == pf::ContactState::Status::kInContact) {
        q = c.joint_angle_rad;
        tip = c.backbone_m.col(c.backbone_m.cols() - 1);
        volume_m3 = pf::suppliedVolumeInContact(model, c, p);  // the held walls keep their growth
      }
    }
    printShape(out, s, q, tip, columns.chord_angle);
    out << ',' << pf::formatExact(volume_m3);
    end_row(p, s, range);
  }
  std::cout << out.str();
}

// Volume as the input closing on @p obstacle: the pressure at which the finger on it has taken @p v
// (gaugeForVolumeInContact, up to @p max_gauge_pa), then the contact rule's shape there. false (the row is nan) with
// a warning once where no pressure up to the top gives it.
bool printVolumeRowInContact(const pf::FingerModel& model, pf::FingerWorkspace& ws, pf::ContactTracker& tracker,
                             double v, const CsvColumns& columns, bool& warned, std::ostream& out,
                             pf::EvaluationReport& report) {
  const pf::PressureRange& range = columns.range;
  const double max_gauge_pa = range.max_gauge_pa;
  double gauge_pa = 0.0;
  std::string why;
  if (!pf::gaugeForVolumeInContact(model, [&tracker](double p) { return tracker.solve(p); }, v, max_gauge_pa,
                                   gauge_pa, why)) {
    if (!warned) std::cerr << "finger_model: warning: " << why << "; such rows are nan\n";
    warned = true;
    return false;
  }
  const pf::FingerState& s = model.evaluate(gauge_pa, ws);
  const pf::ContactState c = tracker.solve(gauge_pa);
  if (c.status == pf::ContactState::Status::kInContact) {
    printShape(out, s, c.joint_angle_rad, c.backbone_m.col(c.backbone_m.cols() - 1), columns.chord_angle);
  } else {
    printShape(out, s, s.joint_angle_rad, s.tip(), columns.chord_angle);
  }
  out << ',' << pf::formatExact(v);
  report = rowReport(s, pf::checkGaugeRange(gauge_pa, range));
  return true;
}

// A volume whose row is nan: the solver's failure, or past the most the model follows.
void warnVolumeNotFollowed(const pf::FingerModel& model, const pf::FingerState& s, double v) {
  std::cerr << "finger_model: warning: "
            << pf::volumeNotFollowedMessage(v, s.status == pf::EvaluationStatus::kSolverFailure, model.volumeLimitM3())
            << "; such rows are nan\n";
}

// Volume as the input: a row per supplied volume, gauge_pa the pressure it makes (docs/MODEL.md, Volume); closing on
// @p obstacle when one is given (then up to @p max_gauge_pa).
void printVolumeCsv(const pf::FingerModel& model, pf::FingerWorkspace& ws, const std::vector<double>& volumes,
                    const CsvColumns& columns) {
  const pf::PressureRange& range = columns.range;
  const int n = model.chamberCount();
  const double max_volume_m3 = pf::maxSuppliedVolumeM3(model, range);  // the range rule, for a volume
  bool warned_clamp = false;
  RowWarnings shape_warnings;  // the backbone crossing itself, as for a pressure
  std::ostringstream out;
  printHeader(out, n, false, columns);  // no blocked force by volume (checkOneInput refuses it)
  bool warned_limit = false, warned_vacuum = false, warned_validated = false;
  std::unique_ptr<pf::ContactTracker> tracker;
  if (columns.obstacle) tracker = std::make_unique<pf::ContactTracker>(model, *columns.obstacle);
  auto end_row = [&](const pf::EvaluationReport& report) {
    if (columns.status) printReport(out, report);
    out << '\n';
  };
  for (double v : volumes) {
    if (tracker && v >= 0.0 && !tracker->outOfReach()) {
      pf::EvaluationReport report{pf::EvaluationStatus::kSolverFailure, 0};  // no pressure up to the top gives it
      if (!printVolumeRowInContact(model, ws, *tracker, v, columns, warned_limit, out, report)) {
        printShapelessVolumeRow(out, n, columns, v);
      }
      end_row(report);
      continue;
    }
    const pf::VolumeCheck in_range = pf::checkVolumeRange(v, max_volume_m3);
    if (in_range.clamped && !RowWarnings::once(warned_clamp)) {
      std::cerr << "finger_model: warning: " << pf::volumeClampedMessage(v, max_volume_m3, range) << "\n";
    }
    const pf::FingerState& s = model.evaluateVolume(in_range.volume_m3, ws);
    if (s.status == pf::EvaluationStatus::kBeyondLimitPoint || s.status == pf::EvaluationStatus::kSolverFailure) {
      if (!RowWarnings::once(warned_limit)) warnVolumeNotFollowed(model, s, v);
      printShapelessVolumeRow(out, n, columns, v);
      end_row(pf::reportEvaluation(s.status, {}, false));
      continue;
    }
    if (s.status == pf::EvaluationStatus::kVacuum && !warned_vacuum) {
      std::cerr << "finger_model: warning: supplied volume " << pf::formatMessage(v)
                << " m^3 draws fluid out: the model has no vacuum; the straight finger is printed, gauge_pa the "
                << "dead gas's pressure (-atmospheric_pressure_pa for an incompressible fluid, dead_volume_m3 = 0: "
                << "it cavitates)\n";
      warned_vacuum = true;
    }
    shape_warnings.noteShape(s);
    printShape(out, s, s.joint_angle_rad, s.tip(), columns.chord_angle);
    out << ',' << pf::formatExact(in_range.volume_m3);
    pf::RangeCheck check;  // a clamped volume is a clamped pressure, as Python and the node report it
    check.clamped = in_range.clamped;
    check.above_validated = in_range.clamped || s.gauge_pa > range.validated_max_gauge_pa;
    if (check.above_validated && !check.clamped && !RowWarnings::once(warned_validated)) {
      std::cerr << "finger_model: warning: " << pf::aboveValidatedMessage(s.gauge_pa, range) << "\n";
    }
    end_row(rowReport(s, check));
  }
  std::cout << out.str();
}

// --obstacle-disk X,Y,R (a far-away unit disk when not given: never read then).
pf::Obstacle parseDisk(const std::string& disk) {
  if (disk.empty()) return pf::Obstacle::disk(0, 0, 1);
  const std::vector<std::string> f = pf::splitFields(disk);
  if (f.size() != 3) throw pf::ParameterError("--obstacle-disk expects X,Y,R, got '" + disk + "'");
  const pf::Obstacle obstacle = pf::Obstacle::disk(pf::parseFiniteOption("--obstacle-disk X", f[0]),
                                                   pf::parseFiniteOption("--obstacle-disk Y", f[1]),
                                                   pf::parseFiniteOption("--obstacle-disk R", f[2]));
  if (!obstacle.problem().empty()) throw pf::ParameterError("--obstacle-disk: " + obstacle.problem());
  return obstacle;
}

// The options of docs/MODEL.md's last sections: volume as the input, and the branch a snap-through starts from.
struct VolumeOptions {
  std::vector<std::string> volumes;
  std::string sweep, start_branch = "near";

  void addTo(CLI::App& app) {
    pf::addRepeatedOption(app, "--supplied-volume-m3", volumes,
                          "volume as the input: the volume V (m^3) a supply has pushed in (chambers' growth plus the "
                          "dead gas's compression); repeat for several rows, which gauge_pa then answers", "M3");
    app.add_option("--sweep-volume-m3", sweep, "FROM:TO:COUNT, evenly spaced supplied volumes (m^3)");
    app.add_option("--start-branch", start_branch,
                   "near (default) or far: the walls' branch the first row starts from (membrane law, a Gent wall "
                   "that snaps through; docs/MODEL.md); the rows then follow the path in order")
        ->check(CLI::IsMember({"near", "far"}));
  }
};

// --supplied-volume-m3 (repeated) or --sweep-volume-m3, finite numbers (m^3).
std::vector<double> parseVolumes(const std::vector<std::string>& volumes, const std::string& volume_sweep) {
  std::vector<double> supplied;
  for (const auto& text : volumes) {  // not finite: the words every interface refuses such a volume with
    const double v = pf::parseNumberOption("--supplied-volume-m3", text);
    if (!std::isfinite(v)) throw pf::ParameterError("--supplied-volume-m3: " + pf::notFiniteVolumeMessage(v));
    supplied.push_back(v);
  }
  if (!volumes.empty() && !volume_sweep.empty()) {
    throw pf::ParameterError("give --supplied-volume-m3 or --sweep-volume-m3, not both");
  }
  if (!volume_sweep.empty()) supplied = parseSweep("--sweep-volume-m3", volume_sweep);
  return supplied;
}

// The time mode's rows: a constant flow fills one finger; each row's time and its pressure, by the regulator's fill law.
void timeModeRows(const pf::FingerParameters& finger, const std::string& flow_lpm, const std::string& duration_s,
                  const std::string& step_s, std::vector<double>& times, std::vector<double>& pressures) {
  if (flow_lpm.empty() || duration_s.empty() || step_s.empty()) {
    throw pf::ParameterError("the time mode needs --flow-lpm, --duration-s and --step-s together");
  }
  const double q = pf::parseFiniteOption("--flow-lpm", flow_lpm);
  const double t_end = pf::parseFiniteOption("--duration-s", duration_s);
  const double dt = pf::parseFiniteOption("--step-s", step_s);
  if (!(q > 0)) throw pf::ParameterError("--flow-lpm = " + flow_lpm + " must be > 0");
  if (!(t_end >= 0)) throw pf::ParameterError("--duration-s = " + duration_s + " must be >= 0");
  if (!(dt > 0) || t_end / dt > 1e7) {
    throw pf::ParameterError("--step-s = " + step_s + " must be > 0 and give at most 10000000 rows");
  }
  // The regulator's fill law (one definition): dP/dt = P_o Q / V_o for one finger.
  const double rate = pf::fillRatePaPerS(q * pf::kM3PerSPerLitrePerMinute, pf::restVolumeM3(finger, 1),
                                         finger.atmospheric_pressure_pa);
  const long rows = static_cast<long>(std::floor(t_end / dt * (1 + 1e-12))) + 1;  // T itself when DT divides it
  for (long k = 0; k < rows; ++k) {
    // k DT to 15 digits: 7 x 0.002 is the time 0.014, not the product's 0.014000000000000002.
    char t[32];
    std::snprintf(t, sizeof t, "%.15g", static_cast<double>(k) * dt);
    times.push_back(std::strtod(t, nullptr));
    pressures.push_back(rate * times.back());
  }
}

// The rows' pressures from --gauge-pa (repeated) or --sweep-pa. NaN and inf are refused here: a pressure the model
// cannot place is an input error, not a row.
std::vector<double> parsePressures(const std::vector<std::string>& gauges, const std::string& sweep) {
  std::vector<double> pressures;
  for (const auto& text : gauges) {  // not finite: the words every interface refuses such a pressure with
    const double p = pf::parseNumberOption("--gauge-pa", text);
    if (!std::isfinite(p)) throw pf::ParameterError("--gauge-pa: " + pf::notFinitePressureMessage(p));
    pressures.push_back(p);
  }
  if (!gauges.empty() && !sweep.empty()) throw pf::ParameterError("give --gauge-pa or --sweep-pa, not both");
  if (!sweep.empty()) pressures = parseSweep("--sweep-pa", sweep);
  return pressures;
}

// A gauge pressure below the vacuum's floor is no input, in the words every interface refuses it with.
void refuseNegativeAbsolute(const std::vector<double>& pressures, double atmospheric_pa) {
  for (double p : pressures) {
    try {
      pf::refuseNegativeAbsolute(p, atmospheric_pa);
    } catch (const pf::ParameterError& e) {
      throw pf::ParameterError(std::string("--gauge-pa: ") + e.what());
    }
  }
}

// Exactly one input, and no blocked force by volume (a plate changes the volume, which is not modelled).
void checkOneInput(const std::vector<double>& pressures, const std::vector<double>& supplied, bool time_mode,
                   bool blocked_tip_force) {
  if (time_mode + !pressures.empty() + !supplied.empty() > 1) {
    throw pf::ParameterError("give one input: pressures, supplied volumes or the time mode");
  }
  if (!time_mode && pressures.empty() && supplied.empty()) {
    throw pf::ParameterError("no pressure given: use --gauge-pa P, --sweep-pa FROM:TO:COUNT, --flow-lpm Q or "
                             "--supplied-volume-m3 V");
  }
  if (!supplied.empty() && blocked_tip_force) {
    throw pf::ParameterError("--supplied-volume-m3 takes no --blocked-tip-force: a finger held straight by a plate "
                             "changes its volume, which is not modelled");
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app(kDescription, "finger_model");
  pf::ParameterOptions parameters;
  parameters.addTo(app);
  std::string solver = "robust", sweep;
  std::vector<std::string> gauges;
  VolumeOptions volume;
  app.add_option("--solver", solver, "robust (default), paper or table");
  // Kept as text: NaN and inf are refused by our own parser, with the option's name.
  // One value per occurrence, repeated for several rows: the help shows "--gauge-pa PA", not "TEXT ...".
  pf::addRepeatedOption(app, "--gauge-pa", gauges, "gauge pressure P (Pa); repeat for several rows", "PA");
  app.add_option("--sweep-pa", sweep, "FROM:TO:COUNT, evenly spaced gauge pressures (Pa)");
  volume.addTo(app);
  Listings listings;
  listings.addTo(app);
  CsvColumns columns;
  std::string max_gauge;
  addColumnOptions(app, columns, max_gauge);
  std::string flow_lpm, duration_s, step_s;
  app.add_option("--flow-lpm", flow_lpm, "time mode: constant air flow Q into the finger (L/min)");
  app.add_option("--duration-s", duration_s, "time mode: fill duration T (s)");
  app.add_option("--step-s", step_s, "time mode: time between rows DT (s)");
  std::string disk;
  app.add_option("--obstacle-disk", disk,
                 "X,Y,R: a disk in the finger's plane (m; x along the unbent finger from the mount, y toward the "
                 "strain-limited side); the finger closes on it instead of passing through");
  return pf::runTool("finger_model", app, argc, argv, [&] {
    if (listings.print(parameters, max_gauge)) return 0;
    std::vector<double> pressures = parsePressures(gauges, sweep);
    const std::vector<double> supplied = parseVolumes(volume.volumes, volume.sweep);
    const bool time_mode = !flow_lpm.empty() || !duration_s.empty() || !step_s.empty();
    checkOneInput(pressures, supplied, time_mode, columns.blocked_tip_force);
    columns.start_far = volume.start_branch == "far";
    columns.range = parameters.loadRange(max_gauge);  // the file's range, --max-gauge-pa on top
    pf::ModelOptions options;
    options.solver = pf::parseSolverName(solver);
    const pf::FingerParameters finger = parameters.load();
    refuseNegativeAbsolute(pressures, finger.atmospheric_pressure_pa);
    std::vector<double> times;
    if (time_mode) timeModeRows(finger, flow_lpm, duration_s, step_s, times, pressures);
    pf::FingerModel model(finger, options);
    pf::FingerWorkspace ws(model);
    const pf::Obstacle obstacle = parseDisk(disk);
    columns.obstacle = disk.empty() ? nullptr : &obstacle;
    if (!supplied.empty()) {
      printVolumeCsv(model, ws, supplied, columns);
      return 0;
    }
    columns.times = times;
    printCsv(model, ws, pressures, columns);
    return 0;
  });
}
