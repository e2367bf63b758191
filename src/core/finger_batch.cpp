// FingerModel::evaluateMany: many pressures in one call, SIMD across pressures where the kernels answer (identical
// chambers: the robust solver's chain, or the membrane and thick wall laws on their near branch), else one at a time
// through the single evaluation.
#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "pneumatic_finger/core/finger_model.hpp"
#include "batch_kernel.hpp"
#include "membrane_kernel.hpp"
#include "simd_kernels.hpp"

namespace pneumatic_finger {

BatchBuffers::BatchBuffers(std::size_t count, int chamber_count) {
  const auto n = static_cast<std::size_t>(chamber_count);
  for (auto* v : {&stretch, &bulge_m, &half_angle_rad, &joint_angle_rad}) v->resize(count * n);
  backbone_m.resize(count * 2 * (n + 2));
  tip_angle_rad.resize(count);
  status.resize(count);
}

BatchOutputs BatchBuffers::outputs() {
  BatchOutputs o;
  o.stretch = stretch.data();
  o.bulge_m = bulge_m.data();
  o.half_angle_rad = half_angle_rad.data();
  o.joint_angle_rad = joint_angle_rad.data();
  o.backbone_m = backbone_m.data();
  o.tip_angle_rad = tip_angle_rad.data();
  o.status = status.data();
  return o;
}

const char* evaluationStatusName(EvaluationStatus status) {
  switch (status) {
    case EvaluationStatus::kOk: return "ok";
    case EvaluationStatus::kVacuum: return "vacuum";
    case EvaluationStatus::kNotFinite: return "not finite";
    case EvaluationStatus::kSolverFailure: return "solver failure";
    case EvaluationStatus::kBeyondLimitPoint: return "beyond limit point";
    case EvaluationStatus::kClamped: return "clamped to max_gauge_pa";
    case EvaluationStatus::kSnappedThrough: return "snapped through";
    case EvaluationStatus::kMeetsItself: return "meets itself";
  }
  return "unknown";
}

const char* batchPathName(BatchPath path) {
  switch (path) {
    case BatchPath::kBest: return "best";
    case BatchPath::kScalar: return "scalar";
    case BatchPath::kGeneric: return "generic";
    case BatchPath::kAvx2: return "avx2";
    case BatchPath::kAvx512: return "avx512";
  }
  return "best";
}

namespace {

// The instruction set of a SIMD path (kBest: the widest this CPU has).
InstructionSet instructionSetOf(BatchPath path) {
  switch (path) {
    case BatchPath::kAvx2: return InstructionSet::kAvx2;
    case BatchPath::kAvx512: return InstructionSet::kAvx512;
    case BatchPath::kGeneric: return InstructionSet::kGeneric;
    case BatchPath::kBest:
    case BatchPath::kScalar:
      break;
  }
  return widestInstructionSet();
}

}  // namespace

bool batchPathAvailable(BatchPath path) {
  return path == BatchPath::kScalar || instructionSetAvailable(instructionSetOf(path));
}

namespace {

// The batch kernels' view of a finger of identical chambers (group @p g, a FingerModel::ChamberGroup).
template <class ChamberGroup>
UniformRobustSpec uniformSpec(const FingerParameters& params, const ChamberGroup& g, const FirstJointSeries& first) {
  return UniformRobustSpec{params.chamber_count, params.atmospheric_pressure_pa, g.shear_modulus_pa,
                           g.chamber_height_m, g.chamber_gap_m, g.wall_critical_height_m,
                           params.base_segment_length_m, params.segment_length_m.data(), params.base_wall_share,
                           first};
}

// @p out moved on by @p rows rows of a finger of @p n chambers.
BatchOutputs offsetOutputs(const BatchOutputs& out, std::size_t rows, std::size_t n) {
  BatchOutputs o = out;
  auto move = [rows](double*& field, std::size_t per_row) {
    if (field) field += rows * per_row;
  };
  move(o.stretch, n);
  move(o.bulge_m, n);
  move(o.half_angle_rad, n);
  move(o.joint_angle_rad, n);
  move(o.backbone_m, 2 * (n + 2));
  move(o.tip_angle_rad, 1);
  if (o.status) o.status += rows;
  return o;
}

// Row @p i of @p out from @p s, or NaN in every output where the row has no shape (@p answered false); the status
// either way.
void writeStateRow(std::size_t i, const FingerState& s, EvaluationStatus status, bool answered, const BatchOutputs& out,
                   std::size_t n) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto row = [n, nan, i, answered](const Eigen::VectorXd& from, double* to) {
    if (!to) return;
    if (answered) std::copy(from.data(), from.data() + n, to + i * n);
    else std::fill(to + i * n, to + (i + 1) * n, nan);
  };
  row(s.stretch, out.stretch);
  row(s.bulge_m, out.bulge_m);
  row(s.half_angle_rad, out.half_angle_rad);
  row(s.joint_angle_rad, out.joint_angle_rad);
  if (out.backbone_m) {
    double* o = out.backbone_m + i * 2 * (n + 2);
    if (answered) std::copy(s.backbone_m.data(), s.backbone_m.data() + 2 * (n + 2), o);
    else std::fill(o, o + 2 * (n + 2), nan);
  }
  if (out.tip_angle_rad) out.tip_angle_rad[i] = answered ? s.tip_angle_rad : nan;
  if (out.status) out.status[i] = static_cast<std::uint8_t>(status);
}

}  // namespace

void FingerModel::evaluateMany(const double* gauge_pa, std::size_t count, const BatchOutputs& out,
                               FingerWorkspace& workspace, BatchPath path) const {
  if (path != BatchPath::kScalar && !batchPathAvailable(path)) {
    throw std::invalid_argument(std::string("evaluateMany: the batch path '") + batchPathName(path) +
                                "' is not available on this CPU or build");
  }
  const auto n = static_cast<std::size_t>(parameters_.chamber_count);
  const SimdKernels* packs = path == BatchPath::kScalar ? nullptr : simdKernels(instructionSetOf(path));
  // The paper law's packs: every pressure is independent of the others.
  if (packs && options_.solver == SolverKind::kRobust && groups_.size() == 1 && !membrane_) {
    packs->batch_uniform_robust(uniformSpec(parameters_, groups_[0], first_joint_series_), gauge_pa, count, out);
    return;
  }
  if (workspace.shape_ != shape_) refuseWorkspace(workspace);
  if (workspace.batch_state_.stretch.size() == 0) workspace.batch_state_ = initialState();
  // The membrane's packs take the runs of pressures on the near branch; the branches are followed here, in order, and
  // the rows off the near branch go one at a time (as does a thick wall without a starting table).
  const MembraneBatchKernel membrane_packs =
      packs && groups_.size() == 1 && membrane_ && groups_[0].membrane.has_guess ? membraneKernel(instructionSetOf(path))
                                                                                 : nullptr;
  const UniformMembraneSpec spec{uniformSpec(parameters_, groups_[0], first_joint_series_), &groups_[0].membrane};
  std::size_t run = 0;  // the first row of the run the packs have not yet taken
  auto takeRun = [&](std::size_t end) {
    if (membrane_packs && end > run) membrane_packs(spec, gauge_pa + run, end - run, offsetOutputs(out, run, n));
  };
  for (std::size_t i = 0; i < count; ++i) {
    const double p = gauge_pa[i];
    const EvaluationStatus branch = std::isfinite(p) ? followBranches(p, workspace) : EvaluationStatus::kOk;
    if (membrane_packs && branch == EvaluationStatus::kOk) continue;  // the near branch: the packs take it with its run
    takeRun(i);
    writeBatchRow(i, p, branch, workspace, out);
    run = i + 1;
  }
  takeRun(count);
}

void FingerModel::writeBatchRow(std::size_t i, double p, EvaluationStatus branch, FingerWorkspace& workspace,
                                const BatchOutputs& out) const {
  FingerState& state = workspace.batch_state_;
  EvaluationStatus status = !std::isfinite(p)                              ? EvaluationStatus::kNotFinite
                            : branch != EvaluationStatus::kOk              ? branch
                            : p < 0.0                                      ? EvaluationStatus::kVacuum
                                                                           : EvaluationStatus::kOk;
  const bool solve = status == EvaluationStatus::kOk || status == EvaluationStatus::kVacuum;
  if (solve && !writeStateAt(p < 0.0 ? 0.0 : p, workspace, state)) status = EvaluationStatus::kSolverFailure;
  if (status == EvaluationStatus::kSnappedThrough && !writeBranchState(p, workspace, state)) {
    status = EvaluationStatus::kSolverFailure;
  }
  const bool answered = status == EvaluationStatus::kOk || status == EvaluationStatus::kVacuum ||
                        status == EvaluationStatus::kSnappedThrough;
  writeStateRow(i, state, status, answered, out, static_cast<std::size_t>(parameters_.chamber_count));
}

void FingerModel::evaluateVolumeMany(const double* supplied_volume_m3, std::size_t count, const BatchOutputs& out,
                                     double* gauge_pa, FingerWorkspace& workspace) const {
  const auto n = static_cast<std::size_t>(parameters_.chamber_count);
  for (std::size_t i = 0; i < count; ++i) {
    const FingerState& s = evaluateVolume(supplied_volume_m3[i], workspace);
    // evaluateVolume keeps the previous numbers where it has no answer; a row of the batch has no previous state.
    const bool answered = s.status == EvaluationStatus::kOk || s.status == EvaluationStatus::kVacuum;
    writeStateRow(i, s, s.status, answered, out, n);
    if (gauge_pa) gauge_pa[i] = answered ? s.gauge_pa : std::numeric_limits<double>::quiet_NaN();
  }
}

}  // namespace pneumatic_finger
