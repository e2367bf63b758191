// Calibration: fit the model's effective parameters (mu, c, the base face's share s0, ...) to what was measured:
// joint angles (the paper's Table 1), tip angles, or tip positions.
//
// The paper compares the average of joints 2..N with its model and calls the model "tuned"; docs/MODEL.md shows its
// published numbers do not come from its own equations. This is the honest version: a documented objective over
// what the data has, a global search (no start point to get wrong), keys the data cannot determine refused, and
// residuals reported.
#pragma once

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/tip_uncertainty.hpp"

namespace pneumatic_finger {

/// One row of measurements. A file gives joint angles, a tip angle, a tip position, or several of them; what a
/// file lacks is empty (joints) or NaN.
struct Measurement {
  int line = 0;                    ///< line number in the file (or row of a table, from 1), for messages
  double gauge_pa = 0.0;           ///< gauge pressure (Pa); NaN where only the supplied volume was measured
  std::vector<double> joint_rad;   ///< measured joint angles q_1..q_N (rad), columns joint_1_rad..joint_N_rad
  double given_average_rad = NAN;  ///< average of joints 2..N read from a column instead (NaN: compute it)
  double tip_angle_rad = NAN;      ///< measured tip direction Theta_N (rad), column tip_angle_rad
  /// measured chord angle (rad), column chord_angle_rad: from the finger's rest direction to the line from its base
  /// O_0 to its tip (chordAngleRad), what one marker tracked on a video gives; about half the tip angle
  double chord_angle_rad = NAN;
  /// measured blocked tip force (N), column blocked_tip_force_n: the finger held straight by a plate at its tip, at
  /// the row's gauge pressure (MODEL.md, "Force"). A row may hold it alone: the force is defined past the limit point
  double blocked_tip_force_n = NAN;
  /// The scale of the force's error (N): the largest measured force of the whole data set, fixed before any fold
  /// leaves rows out (setForceScale); NaN: taken from the rows at hand
  double force_scale_n = NAN;
  double tip_x_m = NAN, tip_y_m = NAN;  ///< measured tip O_{N+1} in the finger's frame (m), columns tip_x_m, tip_y_m
  double supplied_volume_m3 = NAN;  ///< volume the supply pushed in (m^3), column supplied_volume_m3; NaN: not measured
  /// What set the finger's state: its supplied volume (a syringe pump, a displacement-controlled cylinder: the model is
  /// then evaluated by evaluateVolume and its pressure is an output) or, false, its pressure. driveByVolume sets it.
  bool driven_by_volume = false;
  bool in_table = false;  ///< given as columns (Python's dict), not a file: messages say "row", not "line"

  /// "line 7" or, for a table, "row 6": how every message names it.
  std::string where() const { return (in_table ? "row " : "line ") + std::to_string(line); }
  bool hasJoints() const { return !joint_rad.empty(); }
  bool hasGauge() const { return !std::isnan(gauge_pa); }
  bool hasSuppliedVolume() const { return !std::isnan(supplied_volume_m3); }
  bool hasTipAngle() const { return !std::isnan(tip_angle_rad); }
  bool hasChordAngle() const { return !std::isnan(chord_angle_rad); }
  bool hasBlockedForce() const { return !std::isnan(blocked_tip_force_n); }
  /// A row that measured the blocked force and no shape (no joints, tip, chord or tip position).
  bool forceOnly() const { return hasBlockedForce() && !hasJoints() && !hasTipAngle() && !hasChordAngle() && !hasTipPosition(); }
  bool hasTipPosition() const { return !std::isnan(tip_x_m); }

  /// Average of joints 2..N, the quantity the paper compares with the model: the mean of the measured joints, or the
  /// value of the average column when one was named.
  double averageOuterJoints() const;
};

/// Reads measurements. Lines starting with '#' and blank lines are skipped; the first other line is the header:
/// gauge_pa or supplied_volume_m3 (or both), and any of joint_1_rad..joint_N_rad (without a gap, at least two),
/// tip_angle_rad, chord_angle_rad, tip_x_m and tip_y_m (both). When @p average_column is not empty, that column gives the joints 2..N average (e.g. the paper's printed
/// paper_avg_rad, which differs from the mean of its printed joints by up to 0.001 rad).
/// @throws ParameterError naming the file and line: no gauge_pa, none of the measured columns, tip_x_m without
///         tip_y_m, a field that is not a finite number, a row with the wrong number of fields, or fewer than
///         @p min_rows rows
std::vector<Measurement> readMeasurementsCsv(const std::string& path, std::size_t min_rows,
                                             const std::string& average_column = "");

/// Same, from text; @p origin names it in messages.
std::vector<Measurement> parseMeasurementsCsv(const std::string& text, const std::string& origin,
                                              std::size_t min_rows, const std::string& average_column = "");

/// A measurement file's rows, and notes on what it holds that calibration does not read: each such column named,
/// with the column it may have meant ("tip_x_mm": did you mean tip_x_m?). The report prints them as warnings.
struct MeasurementSet {
  std::vector<Measurement> rows;
  std::vector<std::string> notes;
};

/// readMeasurementsCsv and parseMeasurementsCsv with the notes.
MeasurementSet readMeasurementSet(const std::string& path, std::size_t min_rows, const std::string& average_column = "");
MeasurementSet parseMeasurementSet(const std::string& text, const std::string& origin, std::size_t min_rows,
                                   const std::string& average_column = "");

/// Several measurement files as one data set (a bending test and a blocked-force test of the same actuator): their
/// rows one after another, each file read by its own header; the notes name their file where there are several.
MeasurementSet readMeasurementSets(const std::vector<std::string>& paths, std::size_t min_rows,
                                   const std::string& average_column = "");

/// The same from columns (Python's dict of arrays): @p names as a file's header, @p columns[k] the values under
/// names[k], every column as long. Rows are numbered from 1 in messages. @throws ParameterError as the CSV reader,
/// naming the row instead of the line, and for columns of unequal length
MeasurementSet measurementSetFromColumns(const std::vector<std::string>& names,
                                         const std::vector<std::vector<double>>& columns, const std::string& origin,
                                         std::size_t min_rows, const std::string& average_column = "");

/// Marks every row of @p data as set by its supplied volume (Measurement::driven_by_volume), or, with @p by_volume
/// false, by its pressure. @throws ParameterError naming the first line without the column the drive needs
/// (supplied_volume_m3, or gauge_pa)
void driveByVolume(std::vector<Measurement>& data, bool by_volume = true);

/// "pressure" (false) or "volume" (true). @throws ParameterError for anything else.
bool parseDrive(const std::string& name);

/// Fixes every row's force_scale_n to the largest measured blocked force of @p data (1 N where none is above 0), so
/// that a fold without some rows compares forces on the same scale as the whole fit.
void setForceScale(std::vector<Measurement>& data);

/// What a finger can do, checked once before anything is fitted to a measurement (runCalibration calls it, the entry
/// of finger_calibrate and pf.calibrate; calibrate() and leave-one-out, which refit many times, do not): no joint beyond
/// pi rad (each of its two walls turns at most pi/2), no tip angle beyond 2 pi (a full turn), no tip farther from the
/// mount than the finger is long (@p parameters' rest length). Data in degrees, or in mm, fails it by far.
/// @throws ParameterError naming the line, the column, the value, the bound and the likely unit mistake
void checkMeasurementsPlausible(const FingerParameters& parameters, const std::vector<Measurement>& data);

enum class CalibrationObjective {
  kMinimax,       ///< minimise the largest |model - measured| of the joints 2..N averages
  kLeastSquares,  ///< minimise the sum of squared errors of the same averages
  kHuber,         ///< least squares with Huber's robust loss: a term beyond the scale s counts as 2 s |e| - s^2, not
                  ///< e^2, so that an outlying row does not pull the fit. s = 1.345 robust standard deviations of the
                  ///< least-squares fit's terms (1.4826 times their median |e|), fixed before the robust solve
};

/// What the fit compares, model against measured.
enum class CalibrationQuantity {
  kOuterAverage,  ///< "average": the average of joints 2..N, one number per row (the paper's measure)
  kEveryJoint,    ///< "joints": every joint angle, N numbers per row (rad); see calibrate() for base_wall_share
  kFirstJoint,    ///< "joint_1": joint 1 alone, between the passive base segment and chamber 1 (rad)
  kTipAngle,      ///< "tip_angle": the tip direction Theta_N (rad)
  kTipPosition,   ///< "tip_position": the distance of the model's tip from the measured one (m)
  kChordAngle,    ///< "chord_angle": the chord angle, base O_0 to tip (rad; chordAngleRad), as a video that tracks
                  ///< the tip alone measures it. Measured tip positions and joints give it too
  kGauge,         ///< "gauge_pa": the model's pressure at the row's supplied volume against the measured (Pa); needs
                  ///< rows driven by volume with gauge_pa measured
  kTipAngleAndGauge,  ///< "tip_angle+gauge_pa": both at once, rows driven by volume: the tip angle's error (rad) and
                      ///< the pressure's relative error (model/measured - 1), so that 1 degree of bend weighs as
                      ///< 1.75 % of the pressure; a row measured at zero pressure gives its bend alone
  kGaugeAtTipAngle,   ///< "gauge_at_tip_angle": the pressure of the model's equilibrium at each row's measured tip
                      ///< angle against the measured pressure (Pa). Continuous through a snap: under pressure control
                      ///< the bend leaps at the limit point, so a bend error there is a poor residual (the fit learns
                      ///< to avoid the snap), while the pressure that holds a bend is one number on either side of it.
                      ///< A row with a measured bend of zero or less gives no term
};

/// "average", "joints", "joint_1", "tip_angle", "tip_position", "chord_angle", "gauge_pa", "tip_angle+gauge_pa" or
/// "gauge_at_tip_angle". @throws ParameterError for anything else.
CalibrationQuantity parseQuantity(const std::string& name);
const char* quantityName(CalibrationQuantity quantity);

/// The bend "leaps" (a snap-through under pressure control): among the rows set by their pressure, within a window of
/// kLeapWindow of their pressure range (or from one row to the next, where they lie farther apart), the tip angle
/// rises by kLeapShare of its whole range or more, kLeapSteepness times as steeply as on average or more.
inline constexpr double kLeapWindow = 0.05, kLeapShare = 0.25, kLeapSteepness = 3.0;
bool bendLeaps(const std::vector<Measurement>& data);

/// What a file's rows have, in this order of preference: every joint, the tip position, the tip angle, the chord
/// angle; the tip angle compared as the pressure that holds it (gauge_at_tip_angle) where the bend leaps (bendLeaps).
/// @throws ParameterError when @p data is empty
CalibrationQuantity defaultQuantity(const std::vector<Measurement>& data);

/// The keys a fit over @p quantity takes when none are named: shear_modulus_pa and chamber_gap_m, and base_wall_share
/// too when every joint is compared. Under the membrane law, wall_locking_jm as the third key where base_wall_share is
/// not one (the Gent lock shapes the bend's rise after the limit point's bend); the thick wall keeps the file's J_m
/// (--wall-law auto adds it, and kappa, where they predict clearly better: selectModel).
std::vector<std::string> defaultFitKeys(CalibrationQuantity quantity, WallLaw law = WallLaw::kPaper);

/// "minimax", "least_squares" or "huber". @throws ParameterError for anything else.
CalibrationObjective parseObjective(const std::string& name);
const char* objectiveName(CalibrationObjective objective);

/// The keys that may be fitted (scalar over all chambers), and how each is searched.
bool isFittableKey(const std::string& key);

/// Model against one measurement. "Measured" tip angle and position come from the file when it has them, else from
/// the measured joints (their sum, and the backbone of eq 38 with the model's segment lengths), else NaN.
struct Residual {
  double gauge_pa;  ///< the row's pressure: measured where it was, else the model's at the row's supplied volume
  double supplied_volume_m3;  ///< the row's supplied volume (NaN: not measured)
  double measured_gauge_pa, model_gauge_pa;  ///< the pressure: model's differs only where the row is driven by volume
  double measured_avg_rad, model_avg_rad;        ///< joints 2..N (measured NaN without joints)
  double measured_joint1_rad, model_joint1_rad;  ///< joint 1 (the paper left it out)
  std::vector<double> measured_joint_rad, model_joint_rad;  ///< q_1..q_N (measured empty without joints)
  double measured_tip_angle_rad, model_tip_angle_rad;       ///< Theta_N
  double measured_chord_angle_rad, model_chord_angle_rad;   ///< base to tip (chordAngleRad)
  /// The blocked tip force (N; measured NaN where the row has none), and the scale its error is compared in: the
  /// largest measured force of the data, so that the whole force range weighs as 1 rad of bend
  double measured_blocked_force_n, model_blocked_force_n, force_scale_n;
  double measured_tip_x_m, measured_tip_y_m, model_tip_x_m, model_tip_y_m;  ///< O_{N+1}
  /// The pressure of the model's equilibrium at the measured tip angle (Pa); NaN unless gauge_at_tip_angle is compared
  double model_gauge_at_tip_angle_pa;
  double error_rad() const { return model_avg_rad - measured_avg_rad; }
  double joint1_error_rad() const { return model_joint1_rad - measured_joint1_rad; }
  double tip_angle_error_rad() const { return model_tip_angle_rad - measured_tip_angle_rad; }
  double chord_angle_error_rad() const { return model_chord_angle_rad - measured_chord_angle_rad; }
  double blocked_force_error_n() const { return model_blocked_force_n - measured_blocked_force_n; }
  /// The row measured no shape, only the blocked force: its terms are the force's alone.
  bool force_only = false;
  double gauge_error_pa() const { return model_gauge_pa - measured_gauge_pa; }
  double gauge_at_tip_angle_error_pa() const { return model_gauge_at_tip_angle_pa - measured_gauge_pa; }
  /// model/measured - 1 (NaN where the model has no pressure; not defined at a measured zero)
  double gauge_relative_error() const { return gauge_error_pa() / measured_gauge_pa; }
  double tip_position_error_m() const {
    return std::hypot(model_tip_x_m - measured_tip_x_m, model_tip_y_m - measured_tip_y_m);
  }
  /// The numbers a fit over @p quantity compares for this row (rad, m for the tip position, Pa for the pressure; the
  /// tip angle and the pressure's relative error for kTipAngleAndGauge).
  std::vector<double> terms(CalibrationQuantity quantity) const;
  /// The shape's terms alone (terms() adds the blocked force's where the row measured it).
  std::vector<double> shapeTerms(CalibrationQuantity quantity) const;
};

struct CalibrationResult {
  FingerParameters parameters;     ///< @p base with the fitted keys replaced
  std::vector<std::string> keys;   ///< fitted keys
  std::vector<double> values;      ///< their fitted values
  double objective_value = 0.0;    ///< max |error| (rad), sum of squares (rad^2) or sum of Huber's losses (rad^2)
  std::vector<Residual> residuals;
  long model_evaluations = 0;
  /// What the data can tell of each key (calibrationUncertainty): one standard deviation, in the key's unit, from the
  /// fit's curvature (NaN where the data do not determine it), and the keys' correlations (row-major, keys x keys).
  std::vector<double> uncertainty;
  std::vector<double> correlation;
  /// Plain words for what the fit cannot tell: keys that trade off (|correlation| > 0.95), a key on the end of its
  /// search bracket, a key the data do not determine.
  std::vector<std::string> warnings;
};

/// The uncertainty of a fit: J, the derivatives of every compared term with respect to each key (central differences
/// of a millionth of the key's bracket, in the search coordinate: log10 for shear_modulus_pa and wall_locking_jm; a
/// tip position's two components, not its distance), and the terms' own scatter s^2 (the sum of squares left once
/// the keys' directions are taken out, over nu = terms - keys, times nu / (nu - 2): Student's t, since s is itself
/// estimated; no bar below three terms more than keys) give the keys' covariance:
/// - least squares and Huber's loss: s^2 (J^T J)^-1 (Ceres' covariance, by a dense SVD that finds keys the data
///   leave undetermined);
/// - minimax: the covariance of the linearised minimax fit refitted to 200 draws of normal noise of sd s (a
///   parametric bootstrap, minimax_spread.hpp): a minimax fit follows its few largest errors, and scatters more than
///   a least-squares one, the more so the more terms there are.
/// Fills @p result's uncertainty, correlation and warnings.
void calibrationUncertainty(const FingerParameters& base, const std::vector<Measurement>& data,
                            CalibrationQuantity quantity, CalibrationObjective objective, CalibrationResult& result);

/// Residuals of @p parameters against @p data; the pressure at each measured bend (model_gauge_at_tip_angle_pa, two
/// inverse solves a row) only where @p quantity compares it.
std::vector<Residual> residuals(const FingerParameters& parameters, const std::vector<Measurement>& data,
                                CalibrationQuantity quantity = CalibrationQuantity::kOuterAverage);

/// Hears where a long calibration is, step by step ("thick law: leave-one-out, row 5 of 15: 1200 model evaluations");
/// empty: nobody.
using CalibrationProgress = std::function<void(const std::string& step)>;

/// Fits @p keys (any number of isFittableKey, each once) of @p base to @p data over @p quantity.
/// Every joint with base_wall_share and chamber keys is fitted in two stages, each key to the joints it moves: the
/// chamber keys to the joints 2..N average (in the model those joints are all 2 theta, so their average is what the
/// chambers can match), then base_wall_share, which moves joint 1 alone, to joint 1. One search over every joint at
/// once would let the chamber keys trade the outer joints' fit for joint 1's, and under minimax it leaves
/// base_wall_share undetermined wherever joint 1 is not the worst joint.
/// Search: each key over a fixed bracket (mu logarithmically over [1e5, 1e12] Pa for the paper law, [1e4, 1e7] for
/// the others; lengths linearly from 0 to the chamber height; base_wall_share over [0, 1]), global: a coarse scan of
/// the brackets with mu solved at each point, then local solves from the best few points (least squares by Ceres,
/// minimax by NLopt's SLSQP, both polished by Subplex). docs/CALIBRATE.md, "The solver".
/// @throws ParameterError for an unknown, repeated or non-fittable key, no key, a quantity the data
///         lacks, or keys the data cannot determine: as many chamber keys (all but base_wall_share) as rows or
///         more; base_wall_share from the joints
///         2..N average (it moves only joint 1); base_wall_share with another key from tip data alone (the tip
///         angle cannot tell the base face's share from the chambers')
CalibrationResult calibrate(const FingerParameters& base, const std::vector<std::string>& keys,
                            const std::vector<Measurement>& data, CalibrationObjective objective,
                            CalibrationQuantity quantity = CalibrationQuantity::kOuterAverage,
                            const CalibrationProgress& progress = {});

/// Leave-one-out: each row predicted by a fit to the others (the same keys, objective and quantity), as its residual.
/// The brackets are scanned once, on every row; each fold takes its starts from that scan measured without its row
/// (nothing of the held-out row enters its fit) and solves locally from them, as calibrate() does from its own scan. The data needs two rows more than the chamber keys (calibrate()'s rule, one row up). @p progress hears
/// each row's fit begin, named after @p step.
/// @throws ParameterError naming the rows there are and the rows needed
std::vector<Residual> leaveOneOut(const FingerParameters& base, const std::vector<std::string>& keys,
                                  const std::vector<Measurement>& data, CalibrationObjective objective,
                                  CalibrationQuantity quantity, const CalibrationProgress& progress = {},
                                  const std::string& step = "leave-one-out");

/// The objective over leave-one-out residuals, as a fit's objective_value over its own: the largest |error| (minimax)
/// or the sum of squared errors (least squares) of what @p quantity compares; +inf where a row has no shape.
double leaveOneOutObjective(const std::vector<Residual>& leave_one_out, CalibrationQuantity quantity,
                            CalibrationObjective objective);

/// One wall law's calibration: its keys, its fit, and each row predicted by a fit to the others.
struct WallLawFit {
  WallLaw law = WallLaw::kPaper;
  CalibrationQuantity quantity = CalibrationQuantity::kTipAngle;  ///< what the fit compared
  CalibrationResult fit;
  std::vector<Residual> leave_one_out;
  double leave_one_out_objective = 0.0;  ///< leaveOneOutObjective of leave_one_out
  std::string note;  ///< what the law's start changed in the base parameters (empty: nothing), for the report
};

/// `finger_calibrate --wall-law` with keys named: each law of @p laws fitted to @p data (with @p keys, or each law's
/// defaultFitKeys when empty) and predicted row by row (leaveOneOut). With several laws and no keys, runCalibration
/// chooses the keys too (selectModel). A law with more keys fits at least as
/// well; which law the data support is the one that predicts better: chosenWallLaw picks the smallest leave-one-out
/// objective. The membrane law's lever b may exceed the chamber height; the paper law's may not (docs/MODEL.md), so
/// where @p base's does, the paper law starts from its uniform wall, b = L/2, and says so in its note.
/// @throws ParameterError as calibrate() and leaveOneOut() do, naming the law
std::vector<WallLawFit> calibrateWallLaws(const FingerParameters& base, const std::vector<WallLaw>& laws,
                                          const std::vector<std::string>& keys, const std::vector<Measurement>& data,
                                          CalibrationObjective objective, CalibrationQuantity quantity,
                                          const CalibrationProgress& progress = {});

/// The index in @p fits of the smallest leave-one-out objective (the first on a tie).
std::size_t chosenWallLaw(const std::vector<WallLawFit>& fits);

/// "auto" (every law: paper, membrane and thick, each fitted, the best prediction kept), or one law by name ("paper",
/// "membrane", "thick"). @throws ParameterError for anything else.
std::vector<WallLaw> parseWallLawChoice(const std::string& name);

/// The tip's error bar from a calibration: at each row's pressure, the largest of @p fit's and @p leave_one_out's
/// |error| and of the fit's residual scatter (sqrt(sum e^2 / (n - k)) over the rows, k = @p fitted_keys), for the tip
/// angle and for the tip position (NaN where the data measured no tip position): no bar is below the noise the fit
/// leaves, even at a row it happens to hit. The rows of both are the same measurements, in the same order.
/// @p held_out_scale multiplies the leave-one-out's errors: auto's choice among candidates makes its chosen one's too
/// small, and selectionOptimism says by how much (the corrected score over its own; 1: no choice).
TipUncertainty tipUncertainty(const std::vector<Residual>& fit, const std::vector<Residual>& leave_one_out,
                              std::size_t fitted_keys, double held_out_scale = 1.0);

/// The warning for rows the leave-one-out could not predict: the fit has a tip error there but the model fitted
/// without the row has no shape at its pressure (beyond its limit point). Their error bars take the fit's error and
/// the scatter alone, and may be too small there. Empty when every measured row was predicted.
std::string unpredictedRowsWarning(const std::vector<Residual>& fit, const std::vector<Residual>& leave_one_out);

}  // namespace pneumatic_finger
