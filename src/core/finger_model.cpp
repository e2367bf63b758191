#include "pneumatic_finger/core/finger_model.hpp"

#include <algorithm>
#include <atomic>
#include <array>
#include <limits>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "pneumatic_finger/core/units.hpp"
#include "chamber_table.hpp"
#include "simd_kernels.hpp"
#include "uniform_shape.hpp"
#include "wall_chain.hpp"

namespace pneumatic_finger {

const char* solverName(SolverKind kind) {
  switch (kind) {
    case SolverKind::kRobust: return "robust";
    case SolverKind::kPaper: return "paper";
    case SolverKind::kTable: return "table";
  }
  return "robust";
}

SolverKind parseSolverName(const std::string& name) {
  for (SolverKind k : {SolverKind::kRobust, SolverKind::kPaper, SolverKind::kTable}) {
    if (name == solverName(k)) return k;
  }
  throw ParameterError("unknown solver '" + name + "'; known solvers: robust, paper, table");
}

FingerModel::FingerModel(const FingerParameters& parameters, const ModelOptions& options)
    : parameters_(parameters), options_(options), first_joint_series_(firstJointSeries(parameters.base_wall_share)) {
  const int n = parameters_.chamber_count;
  membrane_ = parameters_.wall_law != WallLaw::kPaper;  // the membrane and the thick wall share its code
  if (membrane_ && options_.solver == SolverKind::kPaper) {
    throw ParameterError("the paper solver evaluates the paper's closed forms (eq 10-35), which the membrane wall law "
                         "does not have; use the robust or the table solver with wall_law: membrane");
  }
  group_of_chamber_.resize(static_cast<std::size_t>(n));
  contact_gauge_pa_ = limit_gauge_pa_ = snap_gauge_pa_ = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    ChamberGroup g{parameters_.chamber_height_m[k], parameters_.wall_critical_height_m[k],
                   parameters_.chamber_gap_m[k], parameters_.shear_modulus_pa[k],
                   membrane_ ? parameters_.wall_thickness_m[k] : 0.0, 0.0, MembraneWall{}, {}, 0, 0, 0, 0, 0, {}};
    auto same = [&g](const ChamberGroup& o) {
      return o.chamber_height_m == g.chamber_height_m && o.wall_critical_height_m == g.wall_critical_height_m &&
             o.chamber_gap_m == g.chamber_gap_m && o.shear_modulus_pa == g.shear_modulus_pa &&
             o.wall_thickness_m == g.wall_thickness_m;
    };
    auto it = std::find_if(groups_.begin(), groups_.end(), same);
    if (it == groups_.end()) {
      addGroup(g);
      it = groups_.end() - 1;
    }
    group_of_chamber_[k] = static_cast<int>(it - groups_.begin());
    contact_gauge_pa_ = std::min(contact_gauge_pa_, it->contact_gauge_pa);
    limit_gauge_pa_ = std::min(limit_gauge_pa_, membrane_ ? it->membrane.limit_gauge_pa : limit_gauge_pa_);
    if (membrane_) {  // NaN: not asked (ModelOptions::snap_point)
      snap_gauge_pa_ = options_.snap_point ? std::min(snap_gauge_pa_, it->membrane.snap_gauge_pa)
                                           : std::numeric_limits<double>::quiet_NaN();
    }
  }
  far_turning_gauge_pa_ = -std::numeric_limits<double>::infinity();
  for (const ChamberGroup& g : groups_) {
    if (membrane_ && std::isfinite(g.membrane.far_turning_gauge_pa)) {
      far_turning_gauge_pa_ = std::max(far_turning_gauge_pa_, g.membrane.far_turning_gauge_pa);
    }
  }
  if (!std::isfinite(far_turning_gauge_pa_)) far_turning_gauge_pa_ = std::numeric_limits<double>::infinity();
  // The table holds the paper law's shape; under the membrane law the table solver answers from the robust chain.
  if (options_.solver == SolverKind::kTable && !membrane_) {
    if (groups_.size() == 1) {
      table_shape_writer_ = tableShapeWriterFor(n);
      table_polynomials_ = simdKernels(widestInstructionSet())->table_polynomials;
    }
    for (auto& g : groups_) buildTable(g);
  }
  buildForceModel();
  buildVolumeModel();
  shape_ = static_cast<std::uint64_t>(n) << 32 | static_cast<std::uint64_t>(groups_.size());
  static std::atomic<std::uint64_t> next_id{1};
  id_ = next_id.fetch_add(1, std::memory_order_relaxed);
}

// A new distinct chamber geometry: its contact pressure, and under the membrane law its membrane and limit point.
void FingerModel::addGroup(ChamberGroup g) {
  const double p_o = parameters_.atmospheric_pressure_pa;
  if (membrane_) {
    g.membrane = membraneWall(g.shear_modulus_pa, g.wall_thickness_m, g.chamber_height_m, parameters_.wall_locking_jm,
                              parameters_.wall_law == WallLaw::kThick,
                              parameters_.wall_flexion_face == FlexionFace::kOuter, parameters_.wall_bulge_share);
    if (options_.wall_inverse) buildRisingInverse(g.membrane);
    if (options_.snap_point) setSnapPoint(g.membrane);
    const double p = membraneGaugeForBulge(g.membrane, g.chamber_gap_m);
    g.contact_gauge_pa = std::isnan(p) ? std::numeric_limits<double>::infinity() : p;
  } else {
    g.contact_gauge_pa = pneumatic_finger::contactGaugePa(g.chamber_height_m, g.chamber_gap_m, g.shear_modulus_pa, p_o);
  }
  groups_.push_back(g);
}

FingerWorkspace::FingerWorkspace(const FingerModel& model)
    : shape_(model.shape_),
      state_(model.initialState()),
      far_branch_(model.groups_.size(), 0),
      group_solutions_(model.groups_.size()),
      chamber_half_(static_cast<std::size_t>(model.chamberCount())) {}

// Out of line and cold, so that evaluate()'s check stays one comparison of two numbers.
[[noreturn]] __attribute__((noinline, cold)) void FingerModel::refuseWorkspace(const FingerWorkspace& workspace) const {
  throw std::invalid_argument("FingerModel: the workspace was made for a model of " +
                              std::to_string(workspace.chamber_half_.size()) + " chambers in " +
                              std::to_string(workspace.group_solutions_.size()) + " groups, not this one's " +
                              std::to_string(group_of_chamber_.size()) + " in " + std::to_string(groups_.size()));
}

WallSolution FingerModel::solveMembrane(const ChamberGroup& group, double gauge_pa) {
  return solveMembraneWall(group.membrane, gauge_pa, group.chamber_gap_m, group.wall_critical_height_m);
}

WallSolution FingerModel::solveRobust(const ChamberGroup& group, double gauge_pa, double atmospheric_pa) {
  return solveWall(gauge_pa, atmospheric_pa, group.shear_modulus_pa, group.chamber_height_m, group.chamber_gap_m,
                   group.wall_critical_height_m);
}

// The robust chain's usual path (solveWall's, wall_chain.hpp) inline, its numbers in registers from the pressure to
// the caller: the same operations as solveWall, so the same bits, and finite by construction (s <= 1/20, D <= 1e6).
// false where solveWall's other paths must answer. theta, cos, sin, tan stay as set where the walls are apart.
__attribute__((always_inline)) inline bool FingerModel::usualWall(const ChamberGroup& group, double gauge_pa,
                                                                  double atmospheric_pa, double& stretch_excess,
                                                                  double& bulge_m, HalfAngle& half) {
  const double two_over_b = 2.0 / group.wall_critical_height_m;
  double m = 0.0;
  return wallStagesBySeries(gauge_pa, atmospheric_pa, group.shear_modulus_pa, group.chamber_height_m,
                            group.chamber_gap_m, two_over_b, stretch_excess, bulge_m, m) &&
         (!(bulge_m > group.chamber_gap_m) || usualWallHalfAngle(bulge_m, group.chamber_gap_m, two_over_b, m, half.rad,
                                                                 half.cos, half.sin, half.tan, half.iterations));
}

// The robust chain for one group, the one place that chooses between its paths: the usual path inline (its numbers in
// registers to the caller), else solveRobust, which takes the rare ones (huge pressures, a zero gap) and does not try
// the usual path again. true: the usual path answered, finite by construction, so the caller need not check.
__attribute__((always_inline)) inline bool FingerModel::robustWall(const ChamberGroup& group, double gauge_pa,
                                                                   double atmospheric_pa, double& stretch_excess,
                                                                   double& bulge_m, HalfAngle& half) {
  if (usualWall(group, gauge_pa, atmospheric_pa, stretch_excess, bulge_m, half)) return true;
  const WallSolution w = solveRobust(group, gauge_pa, atmospheric_pa);
  stretch_excess = w.stretch_excess;
  bulge_m = w.bulge_m;
  half = w.half;
  return false;
}

// solveGroup's theta alone, in registers (tipAngleAt, jointAnglesAt); the paper solver by solveGroup.
__attribute__((always_inline)) inline double FingerModel::halfAngleOf(const ChamberGroup& group,
                                                                      double gauge_pa) const {
  if (membrane_) return solveMembrane(group, gauge_pa).half.rad;
  if (options_.solver == SolverKind::kTable) {
    int segment = 0;
    double x = 0.0;
    if (tableSegment(group, gauge_pa, segment, x)) {
      const double theta = tableTheta(group, segment, x);
      return theta > 0.0 ? theta : 0.0;  // a rounding error below 0 next to contact: 0 by definition
    }
    if (!(gauge_pa > group.contact_gauge_pa)) return 0.0;  // walls apart (or NaN, as solveGroup)
  }
  if (options_.solver == SolverKind::kPaper) return solveGroup(group, gauge_pa, false).half.rad;
  // Robust, and the table above its range: as solveGroup takes them, without its other outputs.
  double delta = 0.0, bulge_m = 0.0;
  HalfAngle half;
  robustWall(group, gauge_pa, parameters_.atmospheric_pressure_pa, delta, bulge_m, half);
  return half.rad;
}

ChamberGroupSolution FingerModel::solveGroup(const ChamberGroup& group, double gauge_pa, bool detail) const {
  ChamberGroupSolution r{1.0, 0.0, HalfAngle{}};
  const double p_o = parameters_.atmospheric_pressure_pa;
  if (membrane_) {
    const WallSolution w = solveMembrane(group, gauge_pa);
    return ChamberGroupSolution{1.0 + w.stretch_excess, w.bulge_m, w.half};
  }
  switch (options_.solver) {
    case SolverKind::kRobust: {
      double delta = 0.0;
      robustWall(group, gauge_pa, p_o, delta, r.bulge_m, r.half);
      r.stretch = 1.0 + delta;
      return r;
    }
    case SolverKind::kPaper: {
      r.stretch = paper::stretch(energyGroup(gauge_pa, p_o, group.shear_modulus_pa));
      r.bulge_m = paper::bulge(r.stretch, group.chamber_height_m);
      const double theta = paper::halfAngle(r.bulge_m, group.chamber_gap_m, group.wall_critical_height_m);
      r.half.rad = theta;
      r.half.cos = std::cos(theta);
      r.half.sin = std::sin(theta);
      r.half.tan = r.half.sin / r.half.cos;
      return r;
    }
    case SolverKind::kTable:
      return solveGroupByTable(group, gauge_pa, detail);
  }
  return r;
}

// The table solver: theta (and cos, sin) interpolated within the table, the robust chain above it.
ChamberGroupSolution FingerModel::solveGroupByTable(const ChamberGroup& group, double gauge_pa, bool detail) const {
  ChamberGroupSolution r{1.0, 0.0, HalfAngle{}};
  const double p_o = parameters_.atmospheric_pressure_pa;
  int segment = 0;
  double x = 0.0;
  const bool in_table = tableSegment(group, gauge_pa, segment, x);
  // Above the table the robust chain answers, and it also gives the detail.
  if (!in_table && gauge_pa > group.contact_gauge_pa) {
    double delta = 0.0;
    robustWall(group, gauge_pa, p_o, delta, r.bulge_m, r.half);
    r.stretch = 1.0 + delta;
    return r;
  }
  if (detail) {
    const double delta = stretchExcess(energyGroup(gauge_pa, p_o, group.shear_modulus_pa));
    r.stretch = 1.0 + delta;
    r.bulge_m = bulge(delta, group.chamber_height_m);
  }
  if (!in_table) return r;  // walls apart: theta = 0 exactly
  const auto k = static_cast<std::size_t>(segment);
  const double theta = tableTheta(group, segment, x);
  // Near contact the interpolant may dip a rounding error below 0: theta is 0 there by definition.
  if (!(theta > 0.0)) return r;
  r.half.rad = theta;
  // tan is not tabulated: jointsAndBackbone does not read it, and a shape table's shape comes from the table.
  r.half.tan = std::numeric_limits<double>::quiet_NaN();
  if (group.table_functions == kTableTrigFunctions) {
    const double* row = &group.table[k * kTableTrigFunctions * kTableNodes];
    r.half.cos = tableFunction(row, kTableTrigFunctions, 1, x);
    r.half.sin = tableFunction(row, kTableTrigFunctions, 2, x);
  } else {
    // A shape table has no cos and sin: writeState takes the shape from it directly, and the callers that come
    // here (tipAngleAt, jointAnglesAt) read theta only. NaN, so that nothing can use them unnoticed.
    r.half.cos = r.half.sin = std::numeric_limits<double>::quiet_NaN();
  }
  return r;
}

FingerState restState(const FingerParameters& parameters) {
  const int n = parameters.chamber_count;
  FingerState s;
  s.stretch = Eigen::VectorXd::Ones(n);
  s.bulge_m = Eigen::VectorXd::Zero(n);
  s.half_angle_rad = Eigen::VectorXd::Zero(n);
  s.joint_angle_rad = Eigen::VectorXd::Zero(n);
  s.backbone_m = Eigen::Matrix2Xd::Zero(2, n + 2);
  const std::vector<HalfAngle> straight(static_cast<std::size_t>(n));
  jointsAndBackbone(parameters, straight.data(), s);
  return s;
}

Eigen::Vector2d tipOfJoints(const FingerParameters& parameters, const std::vector<double>& joint_rad) {
  double x = parameters.base_segment_length_m, y = 0.0, dir_c = 1.0, dir_s = 0.0;
  for (std::size_t k = 0; k < joint_rad.size() && k < parameters.segment_length_m.size(); ++k) {
    advanceBackbone(std::cos(joint_rad[k]), std::sin(joint_rad[k]), parameters.segment_length_m[k], dir_c, dir_s, x, y);
  }
  return {x, y};
}

void jointsAndBackbone(const FingerParameters& parameters, const HalfAngle* half, FingerState& out) {
  const int n = parameters.chamber_count;
  // theta_0: the passive base segment's face turns by a share of chamber 1's half angle (0 for an inert face).
  double theta_prev = 0.0, cos_prev = 1.0, sin_prev = 0.0;
  if (n > 0 && parameters.base_wall_share != 0.0) {
    theta_prev = parameters.base_wall_share * half[0].rad;
    sinCosSmall(theta_prev, cos_prev, sin_prev);
  }
  double dir_c = 1.0, dir_s = 0.0, tip_angle = 0.0;
  double x = parameters.base_segment_length_m, y = 0.0;
  bool contact = false;
  out.backbone_m(0, 0) = 0.0;
  out.backbone_m(1, 0) = 0.0;
  out.backbone_m(0, 1) = x;
  out.backbone_m(1, 1) = y;
  for (int i = 0; i < n; ++i) {
    const HalfAngle& h = half[i];
    out.half_angle_rad[i] = h.rad;
    contact = contact || h.rad > 0.0;
    const double q = theta_prev + h.rad;  // eq 37: q_n = theta_{n-1} + theta_n
    out.joint_angle_rad[i] = q;
    tip_angle += q;
    // (cos, sin)(q) = (cos, sin)(theta_{n-1}) * (cos, sin)(theta_n); Theta_n = Theta_{n-1} + q.
    const double rot_c = cos_prev * h.cos - sin_prev * h.sin;
    const double rot_s = sin_prev * h.cos + cos_prev * h.sin;
    advanceBackbone(rot_c, rot_s, parameters.segment_length_m[static_cast<std::size_t>(i)], dir_c, dir_s, x, y);
    out.backbone_m(0, i + 2) = x;
    out.backbone_m(1, i + 2) = y;
    theta_prev = h.rad;
    cos_prev = h.cos;
    sin_prev = h.sin;
  }
  out.tip_angle_rad = tip_angle;
  out.walls_in_contact = contact;
}

FingerState FingerModel::initialState() const {
  FingerState s = restState(parameters_);
  if (!options_.chamber_detail) {
    s.stretch.setConstant(std::numeric_limits<double>::quiet_NaN());
    s.bulge_m.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  return s;
}

inline bool FingerModel::writeTableShape(double gauge_pa, FingerState& out) const {
  const ChamberGroup& group = groups_[0];
  int segment = 0;
  double x = 0.0;
  if (!tableSegment(group, gauge_pa, segment, x)) return false;
  // The table holds the shape: only the detail, when asked for, still runs stages 1-3 (their series).
  double stretch = 1.0, bulge_m = 0.0;
  const bool detail = options_.chamber_detail;
  if (detail) {
    const double delta =
        stretchExcess(energyGroup(gauge_pa, parameters_.atmospheric_pressure_pa, group.shear_modulus_pa));
    stretch = 1.0 + delta;
    bulge_m = bulge(delta, group.chamber_height_m);
  }
  if (!table_shape_writer_(parameters_, table_polynomials_, tableRow(group, segment), x, detail, stretch, bulge_m,
                           out)) {
    return false;  // theta a rounding error below 0 next to contact: solveGroup gives theta = 0, the rest shape
  }
  out.gauge_pa = gauge_pa;
  return true;
}

// The table's shape first, inline in evaluate(); the other paths in a function of their own (noinline), whose prologue
// and register saves the table path would otherwise pay on every call.
inline bool FingerModel::writeState(double gauge_pa, FingerWorkspace& workspace, FingerState& out) const {
  if (table_shape_writer_ && writeTableShape(gauge_pa, out)) return true;
  return writeSolvedState(gauge_pa, workspace, out);
}

__attribute__((noinline)) bool FingerModel::writeSolvedState(double gauge_pa, FingerWorkspace& workspace,
                                                             FingerState& out) const {
  const bool detail = options_.chamber_detail;
  auto finite = [](const ChamberGroupSolution& r) {
    return std::isfinite(r.stretch) && std::isfinite(r.bulge_m) && std::isfinite(r.half.rad) &&
           std::isfinite(r.half.cos) && std::isfinite(r.half.sin);
  };
  // Every group is solved and checked before anything is written, so a failure leaves the previous state whole.
  if (groups_.size() == 1) {
    const ChamberGroup& group = groups_[0];
    const UniformWriter writer = uniformWriterFor(parameters_.chamber_count);
    ChamberGroupSolution r;
    if (options_.solver == SolverKind::kRobust && !membrane_) {
      double delta = 0.0;
      const bool usual = robustWall(group, gauge_pa, parameters_.atmospheric_pressure_pa, delta, r.bulge_m, r.half);
      r.stretch = 1.0 + delta;
      if (!usual && !finite(r)) return false;
    } else {
      r = solveGroup(group, gauge_pa, detail);
      if (!finite(r)) return false;
    }
    writer(parameters_, first_joint_series_, detail, r.stretch, r.bulge_m, r.half.rad, r.half.cos, r.half.sin,
           r.half.tan, out);
    out.gauge_pa = gauge_pa;
    return true;
  }
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    workspace.group_solutions_[g] = solveGroup(groups_[g], gauge_pa, detail);
    if (!finite(workspace.group_solutions_[g])) return false;
  }
  for (std::size_t k = 0; k < group_of_chamber_.size(); ++k) {
    const ChamberGroupSolution& r = workspace.group_solutions_[static_cast<std::size_t>(group_of_chamber_[k])];
    const auto i = static_cast<Eigen::Index>(k);
    if (detail) {
      out.stretch[i] = r.stretch;
      out.bulge_m[i] = r.bulge_m;
    }
    workspace.chamber_half_[k] = r.half;
  }
  jointsAndBackbone(parameters_, workspace.chamber_half_.data(), out);
  out.gauge_pa = gauge_pa;
  return true;
}

// evaluateMany's one-at-a-time path (finger_batch.cpp): writeState out of line.
bool FingerModel::writeStateAt(double gauge_pa, FingerWorkspace& workspace, FingerState& out) const {
  return writeState(gauge_pa, workspace, out);
}

const FingerState& FingerModel::evaluate(double gauge_pa, FingerWorkspace& ws) const {
  if (__builtin_expect(ws.shape_ != shape_, 0)) refuseWorkspace(ws);
  FingerState& state = ws.state_;
  if (!std::isfinite(gauge_pa)) {
    state.status = EvaluationStatus::kNotFinite;
    ws.has_last_ = false;  // the next finite pressure recomputes and resets the status
    return state;
  }
  // Unchanged pressure on the same model: nothing to do. (A workspace of the same shape may have been used with
  // another model last: its state is that model's, so it is recomputed.)
  if (ws.has_last_ && gauge_pa == ws.last_gauge_pa_ && ws.last_model_id_ == id_) return state;
  // +inf under the paper law, and no wall on its far branch: never. Otherwise the walls' branches decide.
  if (__builtin_expect(gauge_pa >= limit_gauge_pa_ || ws.any_far_, 0)) {
    const EvaluationStatus branch = followBranches(gauge_pa, ws);
    if (branch == EvaluationStatus::kBeyondLimitPoint) {
      state.status = branch;
      ws.has_last_ = false;  // the previous numbers stay; the next pressure below the limit recomputes
      return state;
    }
    if (branch == EvaluationStatus::kSnappedThrough) return evaluateFarBranch(gauge_pa, ws);
  }
  const bool vacuum = gauge_pa < 0.0;
  ++ws.computations_;
  if (!writeState(vacuum ? 0.0 : gauge_pa, ws, state)) {
    state.status = EvaluationStatus::kSolverFailure;
    ws.has_last_ = false;
    return state;
  }
  state.gauge_pa = gauge_pa;
  state.status = vacuum ? EvaluationStatus::kVacuum : EvaluationStatus::kOk;
  ws.has_last_ = true;
  ws.last_gauge_pa_ = gauge_pa;
  ws.last_model_id_ = id_;
  return state;
}

bool FingerModel::jointAnglesAt(double gauge_pa, double* q, double* half_angle_rad) const {
  std::array<double, kMaxChamberCount> theta;
  for (std::size_t g = 0; g < groups_.size(); ++g) theta[g] = halfAngleOf(groups_[g], gauge_pa);
  // eq 37: q_n = theta_{n-1} + theta_n; theta_0 = s0 theta_1, the passive base segment's face.
  double previous = parameters_.base_wall_share * theta[static_cast<std::size_t>(group_of_chamber_[0])];
  for (std::size_t k = 0; k < group_of_chamber_.size(); ++k) {
    const double t = theta[static_cast<std::size_t>(group_of_chamber_[k])];
    if (!std::isfinite(t)) return false;
    q[k] = previous + t;
    if (half_angle_rad) half_angle_rad[k] = t;
    previous = t;
  }
  return true;
}

double FingerModel::tipAngleAt(double gauge_pa) const {
  // Theta_N = sum_n q_n = theta_0 + 2 sum_n theta_n - theta_N. The half angles live on the stack (at most the largest
  // chamber_count), not in the model's scratch, so that const methods are safe to call from several threads.
  std::array<double, kMaxChamberCount> theta;
  for (std::size_t g = 0; g < groups_.size(); ++g) theta[g] = halfAngleOf(groups_[g], gauge_pa);
  double sum = 0.0, last = 0.0;
  for (std::size_t k = 0; k < group_of_chamber_.size(); ++k) {
    last = theta[static_cast<std::size_t>(group_of_chamber_[k])];
    sum += last;
  }
  return parameters_.base_wall_share * theta[static_cast<std::size_t>(group_of_chamber_[0])] + (2.0 * sum - last);
}

}  // namespace pneumatic_finger
