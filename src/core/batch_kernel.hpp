// The batch kernel: the robust solver for a finger of identical chambers, SIMD across pressures (each lane of a pack
// is one pressure). Internal header of src/core; see simd_math.hpp for why everything here has internal linkage.
//
// It computes what the single evaluation computes (stages.cpp: solveWall; finger_model.cpp: the uniform joints and
// backbone), so that every lane rounds as the single evaluation does: every stage is the same template, instantiated
// for a pack here and for a double there (wall_chain.hpp: stage 1's product, stage 2's first guess and Halley step,
// stage 3's bulge, the series of stages 2-4 and stage 4's solve; joint_chain.hpp: joint 1's direction, the points).
// What is the kernel's own is the control: where the single evaluation branches, the kernel computes the common
// branch for every lane and selects; an iteration stops per lane where the single one stops, and the pack goes on
// until its last lane stops (lanes that stopped keep their value). The rare branches (energy group > 1e30, bulge
// beyond 1e6 wall heights, a zero gap) are left to the single evaluation, lane by lane.
// test/test_finger_batch.cpp checks the bits against FingerModel::evaluate over ordinary and hard pressures.
#pragma once

#include <cmath>
#include <cstddef>

#include "pneumatic_finger/core/evaluation.hpp"
#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/stages.hpp"
#include "joint_chain.hpp"
#include "wall_chain.hpp"

namespace pneumatic_finger {

/// What the kernel needs of a finger with identical chambers (plain numbers: no Eigen in the kernels).
struct UniformRobustSpec {
  int chamber_count;
  double atmospheric_pa, shear_modulus_pa, chamber_height_m, gap_m, wall_critical_height_m;
  double base_segment_length_m;
  const double* segment_length_m;  ///< chamber_count entries
  double base_wall_share;          ///< s0: theta_0 = s0 theta
  FirstJointSeries first_joint;    ///< firstJointSeries(base_wall_share)
};

namespace {  // NOLINT(build/namespaces)

template <class T>
inline T absOf(T x) {
  return x < splat<T>(0.0) ? -x : x;
}

/// Stages 2-3 stage by stage (stretchExcess, then bulge), for lanes above the series' limit.
template <class T, class M>
inline void stagesTwoThree(const UniformRobustSpec& s, T g, M rare, T& delta_out, T& h_out) {
  const T zero = splat<T>(0.0);
  // Stage 2, stretchExcess: the rational first guess, then Halley until the step is small enough.
  T delta = stretchExcessFirstGuess(g);
  // stretchExcess returns 0 for g = 0, which also a positive pressure gives where P/P_o underflows.
  const auto stretched = g > zero;
  delta = stretched ? delta : zero;
  auto active = stretched & ~rare;
  for (int i = 0; i < 16 && anyOf(active); ++i) {
    const T step = stretchExcessHalleyStep(g, delta);
    delta = active ? delta - step : delta;
    active = active & (absOf(step) > kStretchHalleyStop * delta);
  }

  // Stage 3, bulge.
  h_out = bulgeOf(delta, s.chamber_height_m);
  delta_out = delta;
}

/// Writes lanes [0, valid) of a pack's answers to rows row0.. of @p out: NaN throughout where a pressure was refused
/// or failed (nothing wrong is written as a number).
template <class T>
__attribute__((always_inline)) inline void writeRows(const UniformRobustSpec& s, int valid, std::size_t row0,
                                                     const BatchOutputs& out, std::uint8_t* status, T stretch, T bulge_m, T rad,
                                                     T cos_half, T sin_half, T joint1, T joint, T tip_angle,
                                                     const T* px, const T* py) {
  const int n = s.chamber_count;
  const std::size_t un = static_cast<std::size_t>(n);
  for (int i = 0; i < valid; ++i) {
    const std::size_t row = row0 + static_cast<std::size_t>(i);
    const bool finite = __builtin_isfinite(stretch[i]) && __builtin_isfinite(bulge_m[i]) &&
                        __builtin_isfinite(rad[i]) && __builtin_isfinite(cos_half[i]) &&
                        __builtin_isfinite(sin_half[i]);
    if (status[i] != static_cast<std::uint8_t>(EvaluationStatus::kNotFinite) && !finite) {
      status[i] = static_cast<std::uint8_t>(EvaluationStatus::kSolverFailure);
    }
    if (out.status) out.status[row] = status[i];
    // Nothing wrong is written as a number: a refused or failed pressure is NaN throughout.
    const bool answered = status[i] == static_cast<std::uint8_t>(EvaluationStatus::kOk) ||
                          status[i] == static_cast<std::uint8_t>(EvaluationStatus::kVacuum);
    const double nan = __builtin_nan("");
    if (out.stretch) {
      for (std::size_t k = 0; k < un; ++k) out.stretch[row * un + k] = answered ? stretch[i] : nan;
    }
    if (out.bulge_m) {
      for (std::size_t k = 0; k < un; ++k) out.bulge_m[row * un + k] = answered ? bulge_m[i] : nan;
    }
    if (out.half_angle_rad) {
      for (std::size_t k = 0; k < un; ++k) out.half_angle_rad[row * un + k] = answered ? rad[i] : nan;
    }
    if (out.joint_angle_rad) {
      out.joint_angle_rad[row * un] = answered ? joint1[i] : nan;
      for (std::size_t k = 1; k < un; ++k) out.joint_angle_rad[row * un + k] = answered ? joint[i] : nan;
    }
    if (out.backbone_m) {
      double* o = out.backbone_m + row * 2 * (un + 2);
      o[0] = answered ? 0.0 : nan;
      o[1] = answered ? 0.0 : nan;
      o[2] = answered ? s.base_segment_length_m : nan;
      o[3] = answered ? 0.0 : nan;
      for (std::size_t k = 0; k < un; ++k) {
        o[2 * k + 4] = answered ? px[k][i] : nan;
        o[2 * k + 5] = answered ? py[k][i] : nan;
      }
    }
    if (out.tip_angle_rad) out.tip_angle_rad[row] = answered ? tip_angle[i] : nan;
  }
}

/// Stage 4 for a pack of bulges @p h with m = 2 sqrt(h c)/b (halfAngleOfWall in stages.cpp): walls in contact where
/// h > c, the rest shape elsewhere. Marks in @p rare the lanes its usual form does not take (H >= 1e200, m = 0,
/// D > 1e6), which the caller answers by the single evaluation.
template <class T, class M>
__attribute__((always_inline)) inline void stageFour(T h, T m, double c, double two_over_b, M& rare, T& rad,
                                                     T& cos_half, T& sin_half, T& tan_half) {
  const T zero = splat<T>(0.0), one = splat<T>(1.0);
  const auto contact = h > c;
  const T big_h = h * two_over_b;
  const T num = big_h * ((h - c) * two_over_b), den = big_h + m;
  const T d = num / den;
  rare = rare | (contact & (~(big_h < 1e200) | ~(m > 0.0) | (d > 1e6)));
  rad = zero, cos_half = one, sin_half = zero, tan_half = zero;
  const auto active = contact & ~rare;
  if (anyOf(active)) {
    T rad_c, cos_c, sin_c, tan_c;
    wallHalfAngle(d, m, quarterPowerStart(num, den, d, m), active, rad_c, cos_c, sin_c, tan_c);
    rad = contact ? rad_c : zero;
    cos_half = contact ? cos_c : one;
    sin_half = contact ? sin_c : zero;
    tan_half = contact ? tan_c : zero;
  }
}

/// Stages 1-4 of one pack, as a wall's chain in the single evaluation.
template <class T>
struct WallPack {
  T stretch, bulge_m, rad, cos_half, sin_half, tan_half;
  /// Lane @p i from the single evaluation's wall.
  __attribute__((always_inline)) void setLane(int i, const WallSolution& wall) {
    stretch[i] = 1.0 + wall.stretch_excess;
    bulge_m[i] = wall.bulge_m;
    rad[i] = wall.half.rad;
    cos_half[i] = wall.half.cos;
    sin_half[i] = wall.half.sin;
    tan_half[i] = wall.half.tan;
  }
};

/// Stages 1-4 for a pack of pressures @p p (the lanes refused are 0: the rest shape): the common branch for every
/// lane, the rare lanes (energy group > 1e30, bulge beyond 1e6 wall heights, a zero gap) by the single evaluation.
template <class T>
__attribute__((always_inline)) inline WallPack<T> wallPack(const UniformRobustSpec& s, T p) {
  constexpr int kLanes = lanesOf<T>();
  const T zero = splat<T>(0.0);
  // Stage 1, energyGroup.
  const auto loaded = p > zero;
  T g = energyGroupProduct(p, s.atmospheric_pa, s.shear_modulus_pa);
  g = loaded ? g : zero;
  auto rare = g > splat<T>(kStretchHalleyMaxEnergyGroup);

  // Stages 2-3 as solveWall takes them: by their series in s = sqrt(g/3) where s is below the limit, else stage by stage
  // (a pack computes both only when its lanes straddle the limit).
  const T s_sq = stretchSeriesArgumentSquared(p, s.atmospheric_pa, 1.0 / (3.0 * s.atmospheric_pa * s.shear_modulus_pa));
  const auto series = s_sq <= splat<T>(kStretchSeriesLimit * kStretchSeriesLimit);
  T delta = zero, h = zero, m_series = zero;
  if (anyOf(~series)) {
    T delta_h = zero, h_h = zero;
    stagesTwoThree(s, g, rare, delta_h, h_h);
    delta = delta_h;
    h = h_h;
  }
  const double c = s.gap_m;
  const double two_over_b = 2.0 / s.wall_critical_height_m;
  if (anyOf(series)) {
    T delta_s, h_s;
    const T s_root = sqrtOf(s_sq);
    stretchAndBulgeSeries(s_root, s.chamber_height_m, delta_s, h_s);
    delta = series ? delta_s : delta;
    h = series ? h_s : h;
    m_series = (std::sqrt(s.chamber_height_m * c) * two_over_b) * (sqrtOf(s_root) * bulgeRootSeries(s_root));
  }

  // Stage 4, with m from the series where solveWall takes it.
  const T m = series ? m_series : sqrtOf(h * s.gap_m) * two_over_b;
  T rad, cos_half, sin_half, tan_half;
  stageFour(h, m, s.gap_m, two_over_b, rare, rad, cos_half, sin_half, tan_half);
  WallPack<T> w{1.0 + delta, h, rad, cos_half, sin_half, tan_half};
  // The rare lanes: the single evaluation's own chain.
  for (int i = 0; i < kLanes; ++i) {
    if (rare[i]) {
      w.setLane(i, solveWall(p[i], s.atmospheric_pa, s.shear_modulus_pa, s.chamber_height_m, s.gap_m,
                             s.wall_critical_height_m));
    }
  }
  return w;
}

/// One pack of pressures: lanes [0, valid) are gauge_pa[0..valid), written to rows row0.. of @p out; @p walls(p)
/// gives stages 1-4 of the pack's pressures (wallPack: the paper law; membraneWallPack: the membrane).
template <class T, class Walls>
__attribute__((always_inline)) inline void uniformPack(const UniformRobustSpec& s, const double* gauge_pa, int valid,
                                                       std::size_t row0, const BatchOutputs& out, Walls&& walls) {
  constexpr int kLanes = lanesOf<T>();
  const int n = s.chamber_count;
  std::uint8_t status[kLanes];
  T p;
  for (int i = 0; i < kLanes; ++i) {
    const double x = i < valid ? gauge_pa[i] : 0.0;
    status[i] = !__builtin_isfinite(x) ? static_cast<std::uint8_t>(EvaluationStatus::kNotFinite)
                : x < 0.0              ? static_cast<std::uint8_t>(EvaluationStatus::kVacuum)
                                       : static_cast<std::uint8_t>(EvaluationStatus::kOk);
    p[i] = status[i] == static_cast<std::uint8_t>(EvaluationStatus::kOk) ? x : 0.0;  // vacuum: the rest shape (P = 0)
  }
  const WallPack<T> w = walls(p);
  const T stretch = w.stretch, bulge_m = w.bulge_m, rad = w.rad, cos_half = w.cos_half, sin_half = w.sin_half,
          tan_half = w.tan_half;
  // Stages 5-6 (jointsAndBackboneUniform): q_1 = theta_0 + theta, q_n = 2 theta; the points from uniformPoints.
  const T joint = 2.0 * rad;
  T first_c, first_s;
  const T joint1 = firstJoint(s.base_wall_share, s.first_joint, rad, tan_half, cos_half, sin_half, first_c, first_s);
  T dir_c[kMaxChamberCount], dir_s[kMaxChamberCount], px[kMaxChamberCount], py[kMaxChamberCount];
  if (out.backbone_m) {  // the points only for a caller who asked for them
    uniformPoints<0>(first_c, first_s, cos_half, sin_half, n, s.base_segment_length_m, s.segment_length_m, dir_c,
                     dir_s, px, py, 1);
  }
  const T tip_angle = joint1 + static_cast<double>(n - 1) * joint;
  writeRows<T>(s, valid, row0, out, status, stretch, bulge_m, rad, cos_half, sin_half, joint1, joint, tip_angle, px,
               py);
}

/// A whole batch in packs of T, the last pack partly filled, each pack's walls from @p wall_of (a wall law's pack
/// solver; every law shares the rest of the pipeline, uniformPack).
template <class T, class WallOf>
__attribute__((always_inline)) inline void uniformBatch(const UniformRobustSpec& finger, const double* gauge_pa,
                                                        std::size_t count, const BatchOutputs& out, WallOf wall_of) {
  constexpr std::size_t kLanes = static_cast<std::size_t>(lanesOf<T>());
  for (std::size_t row = 0; row < count; row += kLanes) {
    const std::size_t left = count - row;
    uniformPack<T>(finger, gauge_pa + row, static_cast<int>(left < kLanes ? left : kLanes), row, out, wall_of);
  }
}

/// The paper law's whole batch.
template <class T>
inline void uniformRobustBatch(const UniformRobustSpec& spec, const double* gauge_pa, std::size_t count,
                               const BatchOutputs& out) {
  uniformBatch<T>(spec, gauge_pa, count, out,
                  [&spec](T p) __attribute__((always_inline)) { return wallPack(spec, p); });
}

}  // namespace
}  // namespace pneumatic_finger
