// The batch kernel for the membrane and thick wall laws: a finger of identical chambers on their near branch, SIMD
// across pressures, bit for bit with the single evaluation (membrane_wall.cpp: the wall's inverse, wall_inverse.hpp, or
// without one membraneStretchExcess's table start and Newton steps; stages.cpp: halfAngle; the joints and points as
// batch_kernel.hpp). The inverse's polynomials and the thin law (membrane_law.hpp) run in packs; the thick wall's law,
// where a wall has no inverse, lane by lane. For the Newton steps the kernel's own is the control, as in
// batch_kernel.hpp: each lane starts where the single evaluation starts, and its Newton steps stop where the single
// evaluation's stop (first_zero.hpp, increasingNewtonRoot), the pack going on until its last lane stops.
// The branches are the caller's (FingerModel::evaluateMany follows them in order and hands over the runs of pressures
// on the near branch). Internal header of src/core.
#pragma once

#include <algorithm>

#include "pneumatic_finger/core/membrane_wall.hpp"
#include "batch_kernel.hpp"
#include "membrane_law.hpp"
#include "thick_wall.hpp"
#include "wall_inverse.hpp"

namespace pneumatic_finger {

/// What the membrane kernel needs: the finger, and its chambers' one wall with its starting table.
struct UniformMembraneSpec {
  UniformRobustSpec finger;  ///< shear_modulus_pa unused: the wall holds its law
  const MembraneWall* wall;  ///< with its starting table (has_guess)
};

namespace {  // NOLINT(build/namespaces): internal linkage per instruction set (simd_math.hpp)

/// The wall's law, P and dP/ddelta, for a pack: the thin membrane's in packs (membrane_law.hpp); the thick wall's,
/// whose logarithms, arctangent and cube root have no pack form here, lane by lane through the single evaluation's
/// own function (the same bits by construction), for the lanes in @p active alone: a lane that has stopped is not
/// read (risingNewtonPack masks it), and its law would cost as much as a running one's.
template <class T, class M>
inline void gaugeAndSlopePack(const MembraneWall& w, T x, M active, T& f, T& df) {
  if (!w.thick) return thinGaugeAndSlopeOf(w.pressure_scale_pa, w.locking_jm, x, f, df);
  for (int i = 0; i < lanesOf<T>(); ++i) {
    if (!active[i]) {
      f[i] = 0.0;
      df[i] = 1.0;
      continue;
    }
    double fi = 0.0, dfi = 0.0;
    thickGaugeAndSlope(w, x[i], fi, dfi);
    f[i] = fi;
    df[i] = dfi;
  }
}

/// increasingNewtonRoot (first_zero.hpp) lane by lane on the wall's law, for the lanes in @p active: the same
/// bracket, steps and stopping tests. Returns the lanes' roots (the others' x unchanged).
template <class T, class M>
inline T risingNewtonPack(const MembraneWall& w, T target, T lo, T hi, T x, T prev_x, T prev_df, M active) {
  const auto inside = (x > lo) & (x < hi);
  x = inside ? x : 0.5 * (lo + hi);
  T root = x;
  for (int k = 0; k < 2200 && anyOf(active); ++k) {  // 1100 bisections span every double
    T f, df;
    gaugeAndSlopePack(w, x, active, f, df);
    auto stop = active & (f == target);
    active = active & ~stop;
    const auto below = f < target;
    lo = (active & below) ? x : lo;
    hi = (active & ~below) ? x : hi;
    T next = x - (f - target) / df;
    stop = stop | (active & (absOf(next - x) <= 2e-16 * absOf(x)));  // the step rounds away
    active = active & ~stop;
    const auto newton = (next > lo) & (next < hi);
    next = newton ? next : 0.5 * (lo + hi);
    stop = stop | (active & ~((next > lo) & (next < hi)));  // lo and hi are neighbours
    active = active & ~stop;
    root = stop ? x : root;
    const T step = absOf(next - x);
    const auto known = (prev_x == prev_x) & (prev_x != x);
    const auto converged = active & newton & known &
                           (absOf(df - prev_df) * (step * step) <= 1e-17 * absOf(next) * (absOf(x - prev_x) * (2.0 * df)));
    root = converged ? next : root;
    active = active & ~converged;
    prev_x = active ? x : prev_x;
    prev_df = active ? df : prev_df;
    x = active ? next : x;
  }
  return active ? x : root;  // lanes still going after 2200 steps: their last x, as the single one's
}

/// membraneNewtonStretchExcess for the lanes in @p active of a pack of pressures in [0, limit): the table's node
/// interval per lane, the inverse's cubic Hermite start (tabulatedStretchExcess in membrane_wall.cpp), then the Newton
/// steps. 0 where P = 0.
template <class T, class M>
inline T newtonStretchPack(const MembraneWall& w, T p, M active) {
  constexpr int kLanes = lanesOf<T>();
  T p0, p1, s0, s1, lo, hi;
  for (int i = 0; i < kLanes; ++i) {
    const auto& g = w.guess_gauge_pa;
    const auto node = p[i] > 0.0 ? static_cast<std::size_t>(std::upper_bound(g.begin(), g.end(), p[i]) - g.begin()) - 1
                                 : std::size_t{0};
    p0[i] = g[node];
    p1[i] = g[node + 1];
    s0[i] = w.guess_slope_pa[node];
    s1[i] = w.guess_slope_pa[node + 1];
    lo[i] = w.guess_stretch_excess[node];
    hi[i] = w.guess_stretch_excess[node + 1];
  }
  const T zero = splat<T>(0.0);
  const T dp = p1 - p0, t = (p - p0) / dp;
  const T t2 = t * t, t3 = t2 * t;
  const T hermite =
      (2.0 * t3 - 3.0 * t2 + 1.0) * lo + (t3 - 2.0 * t2 + t) * dp / s0 + (3.0 * t2 - 2.0 * t3) * hi + (t3 - t2) * dp / s1;
  const auto smooth = (s0 > zero) & (s1 > zero) & (dp - dp == zero) & (s1 - s1 == zero);  // x - x == 0: finite
  const T start = smooth ? hermite : lo + t * (hi - lo);
  const auto loaded = active & (p > zero);
  const T delta = risingNewtonPack(w, p, lo, hi, start, lo, s0, loaded);
  return loaded ? delta : zero;
}

/// Stages 1-3 (delta and the bulge h) for a pack of pressures in [0, limit), as solveMembraneWall: the wall's inverse
/// (wall_inverse.hpp) for the lanes at or below its top, with the outer face's stretch where that face bends; the
/// Newton steps for the rest (a wall that rises to its lock, above the inverse's top), their outer face's bulge lane
/// by lane (membraneBulgeM).
template <class T>
inline void membraneStretchAndBulgePack(const MembraneWall& w, T p, T& delta, T& h) {
  const T zero = splat<T>(0.0);
  auto tabulated = p != p;  // none
  if (w.inverse_pieces > 0) {
    tabulated = p <= splat<T>(w.inverse_top_gauge_pa);
    const T p_in = tabulated & (p > zero) ? p : zero;  // +0 at rest, as the Newton steps give
    T outer = zero;
    delta = risingInversePack(w, p_in, w.outer_face_bends ? &outer : nullptr);
    h = w.bulge_per_stretch_m * (w.outer_face_bends ? outer : delta);
    if (!anyOf(~tabulated)) return;
  }
  const T newton = newtonStretchPack(w, p, ~tabulated);
  delta = tabulated ? delta : newton;
  T newton_h = w.bulge_per_stretch_m * newton;  // membraneBulgeM
  if (w.outer_face_bends) {
    for (int i = 0; i < lanesOf<T>(); ++i) newton_h[i] = membraneBulgeM(w, newton[i]);
  }
  h = tabulated ? h : newton_h;
}

/// Stages 1-4 of the membrane or thick wall for a pack of pressures @p p (refused lanes 0: the rest shape), as
/// solveMembraneWall; the rare lanes of stage 4 (and any at or past the limit, which the caller does not send) by the
/// single evaluation.
template <class T>
__attribute__((always_inline)) inline WallPack<T> membraneWallPack(const UniformMembraneSpec& spec, T p) {
  const MembraneWall& wall = *spec.wall;
  const UniformRobustSpec& s = spec.finger;
  auto rare = ~(p < wall.limit_gauge_pa);
  T delta = splat<T>(0.0), h = splat<T>(0.0);
  membraneStretchAndBulgePack(wall, rare ? splat<T>(0.0) : p, delta, h);
  const double two_over_b = 2.0 / s.wall_critical_height_m;
  T rad, cos_half, sin_half, tan_half;
  stageFour(h, sqrtOf(h * s.gap_m) * two_over_b, s.gap_m, two_over_b, rare, rad, cos_half, sin_half, tan_half);
  WallPack<T> w{1.0 + delta, h, rad, cos_half, sin_half, tan_half};
  for (int i = 0; i < lanesOf<T>(); ++i) {
    if (rare[i]) w.setLane(i, solveMembraneWall(wall, p[i], s.gap_m, s.wall_critical_height_m));
  }
  return w;
}

/// The whole run of near-branch pressures in packs of T, the last pack partly filled.
template <class T>
inline void uniformMembraneBatch(const UniformMembraneSpec& spec, const double* gauge_pa, std::size_t count,
                                 const BatchOutputs& out) {
  uniformBatch<T>(spec.finger, gauge_pa, count, out,
                  [&spec](T p) __attribute__((always_inline)) { return membraneWallPack(spec, p); });
}

}  // namespace
}  // namespace pneumatic_finger
