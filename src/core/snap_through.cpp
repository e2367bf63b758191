// The snap-through under pressure control (docs/MODEL.md, "The snap-through"): each chamber group's wall on its near
// or far branch, the path's memory kept in the caller's workspace.
#include <array>
#include <cmath>
#include <limits>

#include "pneumatic_finger/core/finger_model.hpp"
#include "uniform_shape.hpp"

namespace pneumatic_finger {

EvaluationStatus FingerModel::followBranches(double gauge_pa, FingerWorkspace& ws) const {
  if (!membrane_) return EvaluationStatus::kOk;
  std::array<std::uint8_t, kMaxChamberCount> far{};
  bool any_far = false;
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    const MembraneWall& wall = groups_[g].membrane;
    bool on_far = ws.far_branch_[g] != 0;
    if (!on_far && gauge_pa >= wall.limit_gauge_pa) {
      // Past the limit the near branch has no state at this pressure: the wall jumps to the far one, if it has one.
      if (!std::isfinite(wall.far_turning_gauge_pa)) return EvaluationStatus::kBeyondLimitPoint;
      on_far = true;
    } else if (on_far && !(gauge_pa > wall.far_turning_gauge_pa)) {
      on_far = false;  // below the far branch's turning point: back to the near branch
    }
    far[g] = on_far;
    any_far = any_far || on_far;
  }
  for (std::size_t g = 0; g < groups_.size(); ++g) ws.far_branch_[g] = far[g];
  ws.any_far_ = any_far;
  return any_far ? EvaluationStatus::kSnappedThrough : EvaluationStatus::kOk;
}

void FingerModel::startBranch(FingerWorkspace& ws, bool far) const {
  if (ws.shape_ != shape_) refuseWorkspace(ws);
  bool any_far = false;
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    const bool has_far = membrane_ && std::isfinite(groups_[g].membrane.far_turning_gauge_pa);
    ws.far_branch_[g] = far && has_far;
    any_far = any_far || (far && has_far);
  }
  ws.any_far_ = any_far;
  ws.has_last_ = false;  // the cached state may be the other branch's
}

bool FingerModel::writeBranchState(double gauge_pa, FingerWorkspace& ws, FingerState& out) const {
  // Each group's stretch on its own branch, then stages 3-4 from it, then the joints and backbone.
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    const ChamberGroup& group = groups_[g];
    const double delta = ws.far_branch_[g] ? membraneFarStretchExcess(group.membrane, gauge_pa)
                                           : membraneStretchExcess(group.membrane, gauge_pa);
    const WallSolution w = membraneWallAtStretch(group.membrane, delta, group.chamber_gap_m,
                                                 group.wall_critical_height_m);
    if (!std::isfinite(w.half.rad) || !std::isfinite(w.bulge_m)) return false;
    ws.group_solutions_[g] = ChamberGroupSolution{1.0 + w.stretch_excess, w.bulge_m, w.half};
  }
  const bool detail = options_.chamber_detail;
  if (groups_.size() == 1) {
    const ChamberGroupSolution& r = ws.group_solutions_[0];
    uniformWriterFor(parameters_.chamber_count)(parameters_, first_joint_series_, detail, r.stretch, r.bulge_m,
                                                r.half.rad, r.half.cos, r.half.sin, r.half.tan, out);
  } else {
    for (std::size_t k = 0; k < group_of_chamber_.size(); ++k) {
      const ChamberGroupSolution& r = ws.group_solutions_[static_cast<std::size_t>(group_of_chamber_[k])];
      if (detail) {
        out.stretch[static_cast<Eigen::Index>(k)] = r.stretch;
        out.bulge_m[static_cast<Eigen::Index>(k)] = r.bulge_m;
      }
      ws.chamber_half_[k] = r.half;
    }
    jointsAndBackbone(parameters_, ws.chamber_half_.data(), out);
  }
  out.gauge_pa = gauge_pa;
  return true;
}

const FingerState& FingerModel::evaluateFarBranch(double gauge_pa, FingerWorkspace& ws) const {
  FingerState& state = ws.state_;
  ++ws.computations_;
  if (!writeBranchState(gauge_pa, ws, state)) {
    state.status = EvaluationStatus::kSolverFailure;
    ws.has_last_ = false;
    return state;
  }
  state.status = EvaluationStatus::kSnappedThrough;
  ws.has_last_ = true;
  ws.last_gauge_pa_ = gauge_pa;
  ws.last_model_id_ = id_;
  return state;
}

}  // namespace pneumatic_finger
