// The whole finger: pressure in, joint angles and backbone out (docs/MODEL.md stages 1-6).
//
// Only what a scene needs is computed:
//  - chambers with identical (L, b, c, mu) share one solve per pressure;
//  - an unchanged pressure returns the cached state without any work;
//  - the state is allocated once, at construction, and evaluation never allocates.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "pneumatic_finger/core/chord_angle.hpp"
#include "pneumatic_finger/core/evaluation.hpp"
#include "pneumatic_finger/core/membrane_wall.hpp"
#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/stages.hpp"
#include "pneumatic_finger/core/units.hpp"

namespace pneumatic_finger {

/// Which solver turns pressure into half angles.
enum class SolverKind {
  kRobust,  ///< default: cancellation-free stages, safeguarded Halley steps; within 1e-12 rad of the reference
  kPaper,   ///< the paper's closed forms (eq 10-12 Cardano, eq 16-35 Ferrari) with Wang's root check
  kTable,   ///< piecewise polynomial of theta(sqrt(P)) built at construction; robust solver outside its range
};

/// "robust", "paper" or "table".
const char* solverName(SolverKind kind);

/// Parses a solver name. @throws ParameterError naming the unknown solver and the known ones.
SolverKind parseSolverName(const std::string& name);

/// Options of the model that are not properties of the actuator.
struct ModelOptions {
  SolverKind solver = SolverKind::kRobust;
  /// Upper end of the table solver's pressure range (Pa gauge); above it the robust solver answers.
  double table_max_gauge_pa = kModelMaxGaugePa;
  /// Largest error the table may have on its check grid (rad, as tableMeasuredErrorRad() measures it); segments
  /// double until met.
  double table_tolerance_rad = 5e-13;
  /// Compute and write each chamber's stretch and bulge even when the solver does not need them (the table solver
  /// skips the chain). false: the state's stretch and bulge hold NaN (not computed), and no evaluation writes them.
  bool chamber_detail = true;
  /// Under the membrane and thick wall laws, build each wall's inverse (docs/MODEL.md, "The wall's inverse"): an
  /// evaluation then takes a polynomial instead of Newton steps on the law (the same stretch within 4e-15 of itself
  /// and the pressure's rounding), for 20 to 300 microseconds more per wall at construction. The calibration and
  /// the design sweep, which build a model per candidate and evaluate it a few times, build none.
  bool wall_inverse = true;
  /// Under the membrane and thick wall laws, find where each wall snaps (snapGaugePa(); a wall that does not fold
  /// needs about 200 evaluations of its law's slope). The calibration and the design sweep, which do not ask, find
  /// none: snapGaugePa() is then NaN.
  bool snap_point = true;
};

/// Everything the model says about the finger at one pressure. Sized once for N chambers.
struct FingerState {
  double gauge_pa = 0.0;                 ///< pressure the state was computed for (Pa, gauge; 0 for vacuum)
  Eigen::VectorXd stretch;               ///< lambda_n per chamber (-)
  Eigen::VectorXd bulge_m;               ///< h_n per chamber (m)
  Eigen::VectorXd half_angle_rad;        ///< theta_n per chamber (rad)
  Eigen::VectorXd joint_angle_rad;       ///< q_n = theta_{n-1} + theta_n, n = 1..N (rad)
  Eigen::Matrix2Xd backbone_m;           ///< O_0 .. O_{N+1} as columns (m); O_{N+1} is the tip
  double tip_angle_rad = 0.0;            ///< Theta_N: direction of the last segment = sum of joint angles
  bool walls_in_contact = false;         ///< some wall pair pushes (theta_n > 0)
  EvaluationStatus status = EvaluationStatus::kOk;

  /// Tip position O_{N+1}.
  Eigen::Vector2d tip() const { return backbone_m.col(backbone_m.cols() - 1); }
  /// The chord angle, base O_0 to tip (chord_angle.hpp): what a video that tracks the tip alone measures.
  double chordAngle() const { return chordAngleRad(tip().x(), tip().y(), tip_angle_rad); }
};

/// Stages 5-6 (eq 37-38): joint angles q_n = theta_{n-1} + theta_n, the tip direction Theta_N and the backbone
/// O_0..O_{N+1}, from each chamber's half angle (with its cosine and sine). Fills joint_angle_rad, half_angle_rad,
/// backbone_m, tip_angle_rad and walls_in_contact of @p out, which must be sized for parameters.chamber_count.
/// The direction is carried as a unit complex number rotated by (cos, sin) of both half angles, so the whole
/// backbone costs no trigonometric call.
void jointsAndBackbone(const FingerParameters& parameters, const HalfAngle* half_angles, FingerState& out);

/// Eq 38 for joint angles given from outside (measured ones): the tip O_{N+1} of the backbone along @p parameters'
/// segments, joints beyond @p joint_rad's size or the chamber count left out.
Eigen::Vector2d tipOfJoints(const FingerParameters& parameters, const std::vector<double>& joint_rad);

/// A FingerState sized for @p parameters, at rest (the straight finger).
FingerState restState(const FingerParameters& parameters);

/// Every output of FingerModel::evaluateMany for @p count pressures of a finger of @p chamber_count chambers, in
/// arrays it owns (row-major, as BatchOutputs describes them).
struct BatchBuffers {
  BatchBuffers(std::size_t count, int chamber_count);
  std::vector<double> stretch, bulge_m, half_angle_rad, joint_angle_rad, backbone_m, tip_angle_rad;
  std::vector<std::uint8_t> status;
  /// Where evaluateMany writes: every array.
  BatchOutputs outputs();
};

/// One distinct chamber geometry's solve at one pressure: stages 1-4 (a FingerWorkspace's scratch).
struct ChamberGroupSolution {
  double stretch, bulge_m;
  HalfAngle half;
};

class FingerModel;

/// What evaluations write, beside the model that they read (Pinocchio's Data beside its Model): the state of the last
/// evaluate(), the unchanged-pressure cache, and the scratch of unequal chambers and of a batch's one-at-a-time path.
/// All of it is sized at construction, so evaluation never allocates. The caller owns it; one per thread.
class FingerWorkspace {
 public:
  /// A workspace sized for @p model, at the rest shape.
  explicit FingerWorkspace(const FingerModel& model);

  /// The state of the last evaluate() with this workspace (the rest shape before any).
  const FingerState& state() const { return state_; }

  /// How many evaluate() calls did real work (the rest were answered from the cache of the unchanged pressure).
  long computationCount() const { return computations_; }

  /// Whether the walls of chamber group @p group (0-based, as FingerModel numbers them) are on their far branch: they
  /// snapped through at the limit pressure and hold there until the pressure falls to the branch's lower turning
  /// point (docs/MODEL.md, "The snap-through"). The path's memory, read and written by evaluate() and evaluateMany().
  bool onFarBranch(int group) const { return far_branch_.at(static_cast<std::size_t>(group)) != 0; }

  /// Some group is on its far branch.
  bool snappedThrough() const { return any_far_; }

 private:
  friend class FingerModel;
  std::uint64_t shape_;  // the model's chamber and group counts, which size the scratch below
  FingerState state_;
  std::vector<std::uint8_t> far_branch_;  // per group: 1 on the far branch
  bool any_far_ = false;
  bool has_last_ = false;
  double last_gauge_pa_ = 0.0;
  // The model last_gauge_pa_'s state belongs to, by its id: not its address, which a model built after another was
  // destroyed may reuse (a design sweep does just that).
  std::uint64_t last_model_id_ = 0;
  long computations_ = 0;
  std::vector<ChamberGroupSolution> group_solutions_;  // per distinct chamber geometry
  std::vector<HalfAngle> chamber_half_;                // per chamber
  FingerState batch_state_;                            // evaluateMany's one-at-a-time path
};

/// The finger's model: everything fixed at construction (the parameters, the chamber groups, the table), and const
/// after it. Every method is const, so any number of threads may share one model, each with its own FingerWorkspace
/// (test: Concurrency.*, run under ThreadSanitizer by scripts/test.sh).
class FingerModel {
 public:
  /// Builds the model; the table solver also builds, and measures, its table here. Under the membrane wall law the
  /// table solver answers from the robust chain (its table holds the paper law only).
  /// @throws ParameterError for the paper solver with the membrane law, whose stages have no printed closed forms
  explicit FingerModel(const FingerParameters& parameters, const ModelOptions& options = ModelOptions());

  /// Evaluates the finger at @p gauge_pa into @p workspace, and returns its state (valid until the workspace's next
  /// evaluation). The same pressure as the workspace's previous call returns at once. NaN/inf: status kNotFinite and
  /// the previous numbers; negative: status kVacuum and the rest shape.
  /// @throws std::invalid_argument when @p workspace was sized for a model of another shape
  const FingerState& evaluate(double gauge_pa, FingerWorkspace& workspace) const;

  /// The snap-through (docs/MODEL.md): puts every chamber group that has a far branch on it (@p far true) or back on
  /// the near branch, in @p workspace, so that the next evaluation starts from there. A far branch exists where a Gent
  /// wall stiffens again past its limit point (farTurningGaugePa() finite). The next evaluate() recomputes.
  void startBranch(FingerWorkspace& workspace, bool far) const;

  /// The highest pressure (Pa) at which a wall on its far branch snaps back to the near one: the far branches' lower
  /// turning points, the largest of them; +inf where no wall has a far branch (paper law, Neo-Hookean walls).
  double farTurningGaugePa() const { return far_turning_gauge_pa_; }

  /// Evaluates @p count pressures into @p out: for each finite pressure the numbers evaluate() gives, bit for bit;
  /// for a NaN or infinite one, NaN in every output and status kNotFinite (a batch has no "previous state"). The
  /// workspace's state and unchanged-pressure cache are neither read nor written; its walls' branches (membrane law)
  /// are the sequence's start, followed through it in order and left where it ends, as evaluate() leaves them. With identical chambers the
  /// pressures go through in packs of 4 or 8 (SIMD across pressures): the robust solver's (src/core/batch_kernel.hpp),
  /// and the membrane and thick wall laws' runs of pressures on the near branch (src/core/membrane_kernel.hpp);
  /// otherwise one at a time. Used by the Python API and the design sweeps, so that a whole array costs one call.
  /// The one-at-a-time path uses @p workspace's scratch.
  void evaluateMany(const double* gauge_pa, std::size_t count, const BatchOutputs& out, FingerWorkspace& workspace,
                    BatchPath path = BatchPath::kBest) const;

  /// Volume as the input (docs/MODEL.md, "Volume"): evaluates the finger into which a supply has pushed
  /// @p supplied_volume_m3 (m^3, the chambers' growth plus the dead gas's compression, chamber_volume.hpp), and
  /// returns its state, whose gauge_pa is then an output: the pressure the volume makes. Under the membrane law with
  /// identical chambers the volume sets the stretch, and so the shape, before, at and past the pressure's limit point
  /// (the pressure falls there while the volume rises); with unequal chambers it is followed up to that point. Status
  /// kBeyondLimitPoint (previous numbers kept) above volumeLimitM3(); kVacuum for a negative volume (the rest shape,
  /// gauge_pa the dead gas's vacuum, -atmospheric_pressure_pa for an incompressible fluid, which cavitates); kNotFinite
  /// for NaN or inf (previous numbers kept). Always computes (the unchanged-pressure cache is left out and cleared).
  /// The interfaces clamp a volume above maxSuppliedVolumeM3 (pressure_range.hpp) first, as they clamp a pressure.
  /// @throws std::invalid_argument when @p workspace was sized for a model of another shape
  const FingerState& evaluateVolume(double supplied_volume_m3, FingerWorkspace& workspace) const;

  /// Volume as the input for @p count supplied volumes (m^3) in order: row i of @p out holds what evaluateVolume() gives
  /// for supplied_volume_m3[i], bit for bit, and @p gauge_pa[i] (nullptr: not written) the pressure it makes; a volume
  /// evaluateVolume() answers by keeping a previous state (kNotFinite, kBeyondLimitPoint, kSolverFailure) gives NaN in
  /// every output and its status, as evaluateMany() writes a row it cannot evaluate. One volume at a time: the volume's
  /// solve has no pack form. @p workspace's state is that of the last volume afterwards.
  /// @throws std::invalid_argument when @p workspace was sized for a model of another shape
  void evaluateVolumeMany(const double* supplied_volume_m3, std::size_t count, const BatchOutputs& out, double* gauge_pa,
                          FingerWorkspace& workspace) const;

  /// The supplied volume (m^3) at @p gauge_pa: every chamber's growth from its rest volume (by the wall law) plus the
  /// compression of dead_volume_m3 of gas. For a vacuum the chambers stay at rest and the dead gas expands (negative).
  /// NaN at or beyond the limit point (the pressure does not set the volume there) and for NaN. Thread-safe.
  double suppliedVolumeAt(double gauge_pa) const;

  /// The supplied volume (m^3) of a state the model gave (any branch: the far one too), from its bulges and pressure;
  /// NaN where the state holds no bulges (ModelOptions::chamber_detail false) or no pressure.
  double suppliedVolumeOf(const FingerState& state) const;

  /// The same from @p bulge_m, one bulge per chamber (N entries, as FingerState::bulge_m), at @p gauge_pa.
  double suppliedVolumeForBulges(const double* bulge_m, double gauge_pa) const;

  /// Every chamber's bulge (m) at @p gauge_pa into @p bulge_m (N entries; 0 for a vacuum): the free walls' on the
  /// rising branch. false (nothing written) at or beyond the limit point, and for NaN. Thread-safe.
  bool chamberBulgesAt(double gauge_pa, double* bulge_m) const;

  /// Chamber @p chamber's growth from its rest volume (m^3) at the wall bulge @p bulge_m, by the wall law.
  double chamberGrowthM3(int chamber, double bulge_m) const;

  /// The largest supplied volume evaluateVolume() follows (m^3): +inf where the volume sets the shape without end;
  /// with a dead gas volume, the first maximum of the supplied volume along the inflation (where the gas's
  /// expansion, as the pressure falls past the limit point, outpaces the chambers' growth, and the finger snaps even
  /// under volume control); the lock of a Gent wall; with unequal membrane chambers, the volume at the pressure's
  /// limit point.
  double volumeLimitM3() const { return volume_limit_m3_; }

  /// The supplied volume at the pressure's limit point (m^3): a volume above it is past the limit point, where the
  /// pressure falls while the volume grows (+inf without a limit point). Computed once, with the model.
  double limitPointVolumeM3() const { return limit_point_volume_m3_; }

  const FingerParameters& parameters() const { return parameters_; }
  const ModelOptions& options() const { return options_; }
  int chamberCount() const { return parameters_.chamber_count; }

  /// The chamber group (0-based, as FingerWorkspace::onFarBranch() takes it) of chamber @p chamber (0-based).
  int groupOfChamber(int chamber) const { return group_of_chamber_.at(static_cast<std::size_t>(chamber)); }

  /// Number of distinct chamber geometries solved per pressure (1 for identical chambers).
  int distinctChamberCount() const { return static_cast<int>(groups_.size()); }

  /// Gauge pressure (Pa) at which the first wall pair touches (theta leaves 0).
  double contactGaugePa() const { return contact_gauge_pa_; }

  /// The membrane law's limit point (Pa gauge): the lowest pressure maximum of the chambers' walls. At or above it the
  /// pressure does not determine the shape, and evaluations report EvaluationStatus::kBeyondLimitPoint. +inf under
  /// the paper law, or for a Gent wall that locks before any maximum.
  double limitGaugePa() const { return limit_gauge_pa_; }

  /// Where a rising pressure bends the finger fastest (Pa gauge; docs/MODEL.md, "Where it snaps"): the lowest of the
  /// chambers' snap points, each its wall's limit point where it folds, else where the wall is softest (a Gent wall
  /// that locks before it folds: its bend rises steeply but continuously). +inf under the paper law, or where every
  /// wall only stiffens from rest; NaN for a model built without it (ModelOptions::snap_point false).
  double snapGaugePa() const { return snap_gauge_pa_; }

  /// The table's measured error on its check grid (rad): the largest |theta_table - theta_robust|, and for identical
  /// chambers, whose table holds the backbone, also the largest point error divided by the finger's length (the
  /// turn at the base that moves the tip as far). 0 for other solvers.
  double tableMeasuredErrorRad() const { return table_error_rad_; }

  /// Segments per distinct chamber in the table (0 for other solvers).
  int tableSegmentCount() const;

  /// Inverse model: the gauge pressure (Pa) at which the tip direction Theta_N reaches @p tip_angle_rad. Past the
  /// near branch of identical membrane chambers with a far branch (docs/MODEL.md, "The snap-through"), the far
  /// branch's pressure, with @p message saying how to reach it (the snap first).
  /// @param[out] gauge_pa the pressure, when reachable
  /// @param[out] message why not, otherwise; how, for a target on the far branch
  /// @return false when the angle is negative, not finite, or beyond what any pressure up to @p max_gauge_pa gives
  bool gaugeForTipAngle(double tip_angle_rad, double max_gauge_pa, double& gauge_pa, std::string& message) const;

  /// Inverse model for a finger filled by volume: the supplied volume (m^3) at which the tip direction reaches
  /// @p tip_angle_rad. For identical membrane chambers the volume holds every angle up to volumeLimitM3(), before, at
  /// and past the pressure's limit point (no snap: under volume control the state is unique); otherwise the volume at
  /// gaugeForTipAngle's pressure.
  /// @return false, with @p message saying why, for an angle that is negative, not finite, beyond what volume control
  ///         follows, or needs more than @p max_volume_m3
  bool volumeForTipAngle(double tip_angle_rad, double max_volume_m3, double& volume_m3, std::string& message) const;

  /// Identical chambers only: the gauge pressure (Pa) at which every wall's half angle is @p half_angle_rad (> 0),
  /// in closed form. False for unequal chambers, or an angle no pressure gives.
  bool gaugeForHalfAngle(double half_angle_rad, double& gauge_pa) const;

  /// Tip direction Theta_N at @p gauge_pa without touching the cached state (for inversion and calibration). NaN at or
  /// beyond the limit point.
  double tipAngleAt(double gauge_pa) const;

  /// The largest pressure below the limit point (the double just under limitGaugePa(); +inf without one).
  double belowLimitGaugePa() const;

  /// The tip direction there: the most the model holds (+inf without a limit point).
  double tipAngleBelowLimit() const;

  /// The force model (docs/MODEL.md, "Force"; src/core/finger_force.cpp). The moment (N m) that the walls at each
  /// joint of the straight finger exert at @p gauge_pa, into @p moment_nm (N entries, joint 1 first): the chamber's
  /// pressure on the strip of its wall flattened against the neighbour's, at the lever b. 0 up to the contact pressure
  /// and for a vacuum; NaN for a NaN pressure. At or beyond a membrane or thick wall's limit point (a rising pressure:
  /// the free wall has snapped) the strip is the whole wall, so the moment jumps there as the free bend does.
  void straightJointMomentsNm(double gauge_pa, double* moment_nm) const;

  /// The moments (N m) at the joints of a finger whose joint j has been held since the pressure
  /// @p held_since_gauge_pa[j] (NaN: free, and 0 moment), at @p gauge_pa: as straightJointMomentsNm, with each held
  /// wall's contact plane where its free bulge was at that pressure (c if before contact). The contact rule's
  /// ContactState::held_since_gauge_pa is this input; contactNormalForcesN shares these moments among the contacts.
  void heldJointMomentsNm(double gauge_pa, const double* held_since_gauge_pa, double* moment_nm) const;

  /// Joint @p joint's (0-based) compliance weight in the force model: 2 (two walls turn it), 1 + s0 for joint 1.
  double jointComplianceWeight(int joint) const;

  /// The blocked tip force (N) at @p gauge_pa: the finger held straight by a plate at its tip, orthogonal to the
  /// bending plane. The joints' moments are shared by their compliance, linear about the straight finger (the planar
  /// static balance with the tip held): F = sum_j M_j l_j w_j / sum_j l_j^2 w_j, l_j the joint's distance to the tip,
  /// w_j its compliance (2 walls, or 1 + s0 at joint 1). Same NaN and 0 cases as straightJointMomentsNm.
  double blockedTipForceN(double gauge_pa) const;

  /// The free joint angles q_1..q_N at @p gauge_pa (>= 0) into @p joint_angle_rad (N entries), and, when not null,
  /// the half angles theta_1..theta_N into @p half_angle_rad, without touching the cached state (thread-safe like
  /// tipAngleAt). @return false when the solver found no finite answer.
  bool jointAnglesAt(double gauge_pa, double* joint_angle_rad, double* half_angle_rad = nullptr) const;

 private:
  struct ChamberGroup {
    double chamber_height_m, wall_critical_height_m, chamber_gap_m, shear_modulus_pa, wall_thickness_m;
    double contact_gauge_pa;
    MembraneWall membrane;  // the membrane law's wall (unused under the paper law)
    // Table solver: piecewise degree-7 polynomials in u = sqrt(P) (chamber_table.cpp, buildTable). Per segment, the
    // 8 monomial coefficients (in the local variable x in [-1, 1]) of every function, interleaved (coefficient i of
    // function f at i * table_functions + f) so that one coefficient of all functions is one run of memory. The
    // functions: for unequal chambers theta, cos theta, sin theta (the backbone is then composed per chamber); for
    // identical chambers, the whole published shape: theta, then the points O_2..O_{N+1} (x, y), then zeros that
    // round the count up to whole SIMD packs. Either way theta is function 0.
    std::vector<double> table;
    double table_u_begin = 0.0, table_u_end = 0.0, table_inv_width = 0.0;
    int table_segments = 0;
    int table_functions = 0;
    // theta's coefficients alone again, 8 per segment (one cache line): for the callers that want theta only
    // (tipAngleAt, jointAnglesAt), which in the interleaved rows would touch 8 lines.
    std::vector<double> table_theta_only;
  };

  /// The membrane law's chain (stages 1-4) for one group: NaN at or beyond its limit point.
  static WallSolution solveMembrane(const ChamberGroup& group, double gauge_pa);
  /// The constructor's step for a new distinct chamber geometry (contact pressure, membrane).
  void addGroup(ChamberGroup group);
  /// The robust chain (stages 1-4) for one group of identical chambers.
  static WallSolution solveRobust(const ChamberGroup& group, double gauge_pa, double atmospheric_pa);
  /// The usual path, else solveRobust: the robust chain for one group (finger_model.cpp). true: the usual path
  /// answered.
  static bool robustWall(const ChamberGroup& group, double gauge_pa, double atmospheric_pa, double& stretch_excess,
                         double& bulge_m, HalfAngle& half);
  /// solveRobust's usual path inline (finger_model.cpp); false where solveRobust must answer.
  static bool usualWall(const ChamberGroup& group, double gauge_pa, double atmospheric_pa, double& stretch_excess,
                        double& bulge_m, HalfAngle& half);
  ChamberGroupSolution solveGroup(const ChamberGroup& group, double gauge_pa, bool detail) const;
  ChamberGroupSolution solveGroupByTable(const ChamberGroup& group, double gauge_pa, bool detail) const;
  /// solveGroup's half angle alone (finger_model.cpp).
  double halfAngleOf(const ChamberGroup& group, double gauge_pa) const;
  /// The table's theta in @p segment at @p x (table_theta_only).
  static double tableTheta(const ChamberGroup& group, int segment, double x);
  /// The chamber table (chamber_table.cpp): built, interpolated, measured.
  void buildTable(ChamberGroup& group);
  void interpolateTable(ChamberGroup& group, double u_begin, double u_end, int segments, FingerState& scratch) const;
  double tableErrorRad(const ChamberGroup& group, FingerState& exact_state, FingerState& table_state) const;
  void exactTableFunctions(const ChamberGroup& group, double u, FingerState& scratch, double* f) const;
  /// Where @p gauge_pa falls in @p group's table: false outside it (at or below contact, above its range, or no
  /// table), else the segment and the local variable x in [-1, 1].
  static bool tableSegment(const ChamberGroup& group, double gauge_pa, int& segment, double& x);
  /// The coefficients of @p group's table for @p segment.
  static const double* tableRow(const ChamberGroup& group, int segment);
  /// Writes the state at @p gauge_pa into @p out; returns false, leaving @p out untouched, when the solver gave a
  /// non-finite stretch, bulge or half angle.
  bool writeState(double gauge_pa, FingerWorkspace& workspace, FingerState& out) const;
  /// writeState out of line, for evaluateMany's one-at-a-time path and the volume input (other translation units).
  bool writeStateAt(double gauge_pa, FingerWorkspace& workspace, FingerState& out) const;
  /// evaluateMany's row @p i one at a time, at @p p with its branch @p branch already followed (finger_batch.cpp).
  void writeBatchRow(std::size_t i, double p, EvaluationStatus branch, FingerWorkspace& workspace,
                     const BatchOutputs& out) const;
  /// writeState's table path (identical chambers, table_shape_writer_ set): false where the table does not answer
  /// (outside its range, or theta a rounding error below 0 next to contact; the points may then be written).
  bool writeTableShape(double gauge_pa, FingerState& out) const;
  /// writeState's other paths: the solver per group, then the joints and backbone.
  bool writeSolvedState(double gauge_pa, FingerWorkspace& workspace, FingerState& out) const;
  /// The force model's constants, computed once (finger_force.cpp): per joint its pushing walls, distance to the
  /// tip and compliance weight.
  void buildForceModel();
  /// The free bulge h (m) of @p group's wall at @p gauge_pa (stages 1-3; 0 for P <= 0; at or beyond the limit
  /// point the far branch's, or +inf where the wall balloons without bound).
  double freeBulgeM(const ChamberGroup& group, double gauge_pa) const;
  /// The height 2a (m) of the strip of @p group's wall pressed flat against its neighbour's at @p gauge_pa, the
  /// contact plane at bulge @p plane_bulge_m.
  double contactStripHeightM(const ChamberGroup& group, double gauge_pa, double plane_bulge_m) const;
  /// The strip's height for a free bulge @p bulge_m already solved.
  double stripHeightM(const ChamberGroup& group, double bulge_m, double plane_bulge_m) const;
  /// The moment (N m) at joint @p joint (0-based) at @p gauge_pa (not NaN), from each group's strip (indexed by
  /// group).
  double jointMomentNm(std::size_t joint, double gauge_pa, const double* strip_m) const;
  /// The walls' branches at @p gauge_pa (snap_through.cpp): each group on the near branch jumps to its far branch at
  /// or above its limit pressure, and one on the far branch falls back at or below its far turning point. Returns
  /// kBeyondLimitPoint (branches unchanged) where a wall passes its limit without a far branch, kSnappedThrough where
  /// some group is on its far branch, else kOk.
  EvaluationStatus followBranches(double gauge_pa, FingerWorkspace& workspace) const;
  /// The state with some group on its far branch into @p out (gauge_pa included); false for a non-finite answer.
  bool writeBranchState(double gauge_pa, FingerWorkspace& workspace, FingerState& out) const;
  /// evaluate()'s far-branch path: writeBranchState into the workspace's state, with status and cache.
  const FingerState& evaluateFarBranch(double gauge_pa, FingerWorkspace& workspace) const;
  /// gaugeForTipAngle on the near branch: its pressure, inf where none up to @p max_gauge_pa (finger_inverse.cpp).
  double gaugeOnNearBranch(double tip_angle_rad, double turns, double max_gauge_pa) const;
  /// gaugeForTipAngle past the near branch, for identical chambers with a far branch (finger_inverse.cpp).
  bool gaugeOnFarBranch(double half_angle_rad, double tip_angle_rad, double max_gauge_pa, double& gauge_pa,
                        std::string& message) const;
  /// The volume model's constants (finger_volume.cpp): each group's volume coefficient and the volume's limit.
  void buildVolumeModel();
  void buildVolumeGuess();
  /// Group @p group's chambers' growth (m^3) at bulge @p bulge_m (finger_volume.cpp).
  double groupGrowthM3(std::size_t group, double bulge_m) const;
  /// The supplied volume (m^3) of identical membrane chambers at stretch excess @p delta (>= 0, below the lock).
  double suppliedVolumeAtStretch(double delta) const;
  // Identical membrane chambers: the stretch excess at which the supply has pushed in @p v (m^3, below
  // volume_limit_m3_): closed-form for an incompressible fluid, else Newton steps on V_s(delta).
  double stretchForSuppliedVolume(double v) const;
  /// The state of identical membrane chambers at stretch excess @p delta, found for the supplied volume
  /// @p supplied_volume_m3, into @p out (gauge_pa included); false for a non-finite pressure or half angle, or a
  /// stretch that does not hold that volume (next to a lock, where no double does).
  bool writeStretchState(double delta, double supplied_volume_m3, FingerState& out) const;
  /// Throws: @p workspace was sized for a model of another shape (evaluate(), evaluateMany()).
  [[noreturn]] void refuseWorkspace(const FingerWorkspace& workspace) const;
  /// The rest shape, with NaN for stretch and bulge when the options leave them out (chamber_detail false).
  FingerState initialState() const;
  friend class FingerWorkspace;

  FingerParameters parameters_;
  ModelOptions options_;
  FirstJointSeries first_joint_series_;  // joint 1's direction for identical chambers (stages.hpp)
  std::vector<ChamberGroup> groups_;
  // The table solver with identical chambers: writes the state from the table's shape (uniform_shape.hpp,
  // tableShape) with the polynomials of the widest instruction set the CPU has; null otherwise.
  void (*table_polynomials_)(const double*, int, int, double, double*) = nullptr;
  bool (*table_shape_writer_)(const FingerParameters&, void (*)(const double*, int, int, double, double*),
                              const double*, double, bool, double, double, FingerState&) = nullptr;
  std::vector<int> group_of_chamber_;
  double contact_gauge_pa_ = 0.0;
  double limit_gauge_pa_ = 0.0;
  double far_turning_gauge_pa_ = 0.0;  // farTurningGaugePa()
  double snap_gauge_pa_ = 0.0;  // snapGaugePa()
  // The force model (buildForceModel): per joint, the chambers whose walls push at it (joint 1: chamber 1 and the
  // base face, so both are chamber 0), its distance to the tip (m) and its compliance weight; per chamber e b (m^2),
  // the strip's width times its lever. For identical chambers the tip force is one product with
  // uniform_force_lever_ = sum_j l_j w_j / sum_j l_j^2 w_j (1/m; 0 otherwise).
  struct ForceJoint {
    int chamber_a, chamber_b;
    double tip_distance_m, weight;
  };
  std::vector<ForceJoint> force_joints_;
  std::vector<double> push_lever_m2_;
  double force_l2w_ = 0.0;  // sum_j l_j^2 w_j (m^2)
  double uniform_force_lever_ = 0.0;
  // The volume model (buildVolumeModel): per group, what multiplies its state's growth: under the membrane law the
  // group's rest volume sum V_o (m^3, times lambda^3 - 1), under the paper law its sum (pi/2) L e (m^2, times h).
  std::vector<double> volume_coefficient_;
  std::vector<double> chamber_volume_coefficient_;  // the same per chamber (chamberGrowthM3)
  bool volume_by_stretch_ = false;  // identical membrane chambers: the volume input is solved in delta, past the limit
  double volume_limit_stretch_excess_ = 0.0;  // delta where volumeLimitM3() is reached (volume_by_stretch_)
  // With a gas in the drive (volume_by_stretch_): the supplied volume and dV/ddelta at the wall's starting-table nodes,
  // where the volume input's Newton steps start (stretchForSuppliedVolume), as the pressure's do from P there.
  bool has_volume_guess_ = false;
  std::array<double, MembraneWall::kGuessNodes + 1> volume_guess_m3_{}, volume_guess_slope_m3_{};
  double limit_point_volume_m3_ = std::numeric_limits<double>::infinity();
  double volume_limit_m3_ = 0.0;
  bool membrane_ = false;  // the membrane wall law (parameters_.wall_law)
  double table_error_rad_ = 0.0;
  std::uint64_t shape_ = 0;  // chamber count << 32 | group count: what a workspace must have been sized for
  std::uint64_t id_;         // unique per construction (a copy shares it: the same model); keys a workspace's cache
};

/// Gauge pressure (Pa) at which a chamber's bulge reaches its gap (the contact pressure): the inverse chain
/// h = c -> delta -> g -> P, all in closed form.
double contactGaugePa(double chamber_height_m, double chamber_gap_m, double shear_modulus_pa,
                      double atmospheric_pa);

/// Inverse stages 3 -> 1: the gauge pressure (Pa) that produces bulge @p bulge_m (m).
double gaugeForBulge(double bulge_m, double chamber_height_m, double shear_modulus_pa, double atmospheric_pa);

}  // namespace pneumatic_finger
