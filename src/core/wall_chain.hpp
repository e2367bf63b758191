// Stages 2-4 of docs/MODEL.md written once, for a plain double and for a pack of doubles: the usual path of the robust
// chain (the series of stages 2-3 in s = sqrt(g/3), and stage 4's safeguarded solve). The single evaluation
// (finger_model.cpp, stages.cpp) and the batch kernel (batch_kernel.hpp) instantiate the same templates, so both round
// alike. Internal header of src/core; internal linkage as in simd_math.hpp.
#pragma once

#include "simd_math.hpp"

namespace pneumatic_finger {
namespace {  // NOLINT(build/namespaces): internal linkage per instruction set (simd_math.hpp)

/// Stage 1's energy group g = (P/P_o)(2 P_o + P)/mu, a product of O(1) factors: ((P_abs/P_o)^2 - 1) would cancel for
/// small P. (energyGroup, stages.cpp, also clamps it to kMaxEnergyGroup; the batch leaves huge ones to it.)
template <class T>
inline T energyGroupProduct(T gauge_pa, double atmospheric_pa, double shear_modulus_pa) {
  return (gauge_pa / atmospheric_pa) * ((2.0 * atmospheric_pa + gauge_pa) / shear_modulus_pa);
}

/// Above this energy group, the stretch polynomial's products would overflow: a fixed point answers (stages.cpp).
constexpr double kStretchHalleyMaxEnergyGroup = 1e30;

/// Stage 2's first guess: a rational function of s = sqrt(g/3) that matches both ends of the root,
/// delta = s + s^2/3 - s^3/18 + ... (g -> 0) and delta = sqrt(g) - 1 + ... (g -> inf): within 0.43 % everywhere.
template <class T>
inline T stretchExcessFirstGuess(T g) {
  const T s = sqrtOf(g * (1.0 / 3.0));
  return s * (1.0 + s * (1.2637079407904241 + s * 0.602317462994015)) /
         (1.0 + s * (0.9303746074570908 + s * 0.34774814939720705));
}

/// One Halley step on F(delta) = delta^2 (3 + delta) - g (1 + delta), the step to subtract. No cancellation at the
/// root beyond F's own (|F| errs by ~ulp(g), F' ~ 6 delta, so delta keeps its relative accuracy even as delta -> 0),
/// F' > 0 there, and for g <= kStretchHalleyMaxEnergyGroup no product overflows. Cubic convergence: from 0.43 %, two
/// steps.
template <class T>
inline T stretchExcessHalleyStep(T g, T delta) {
  const T f = delta * delta * (3.0 + delta) - g * (1.0 + delta);
  const T fp = delta * (3.0 * delta + 6.0) - g;
  const T fpp = 6.0 * delta + 6.0;
  return 2.0 * f * fp / (2.0 * fp * fp - f * fpp);
}

/// After a Halley step of relative size r the error is O(r^3): below 1e-16 once r < this.
constexpr double kStretchHalleyStop = 4e-6;

/// Stage 3: the bulge h of a wall of height L from the stretch excess delta, without cancellation for small delta.
template <class T>
inline T bulgeOf(T stretch_excess, double chamber_height_m) {
  const T d = stretch_excess;
  return chamber_height_m * d * (2.0 + d) / (sqrtOf(1.0 + d * (4.0 + 2.0 * d)) + 1.0);
}

/// Stages 2 and 3 together (docs/MODEL.md) for small energy groups: with s = sqrt(g/3) <= 1/20, the stretch excess
/// delta and the bulge h as power series in s, delta = s (1 + s/3 - s^2/18 - ...) and h = L s (1 - s/6 + 11 s^2/18 - ...).
/// Both come from s at once, so the chain skips the cubic's Halley steps and the bulge's square root and division
/// (together about as long as the rest of the chain). The coefficients and their error are derived exactly by
/// scripts/wall_series.py: the terms left out are below 6e-21 (delta) and 1.3e-18 (h) relative, well below the
/// rounding of the sums (test: Stage23Series). The limit covers the calibrated finger to 3.4e5 Pa, beyond its
/// validated range (2 kg/cm^2) and the table's (3 kg/cm^2); above it the Halley steps answer.
constexpr double kStretchSeriesLimit = 0.05;
template <class T>
inline void stretchAndBulgeSeries(T s, double chamber_height_m, T& stretch_excess, T& bulge_m) {
  static constexpr double kStretch[13] = {1.0, 0.3333333333333333, -0.05555555555555555, -0.037037037037037035,
                                          0.023148148148148147, 0.00411522633744856, -0.009002057613168725,
                                          0.0013717421124828531, 0.0030423620637098003, -0.0015749631661840166,
                                          -0.0007487822613422751, 0.0009427198880026193, 5.518236619869374e-06};
  static constexpr double kBulge[19] = {1.0, -0.16666666666666666, 0.6111111111111112, -1.287037037037037,
                                        2.7453703703703702, -6.276748971193416, 15.046553497942387,
                                        -37.20413237311386, 94.16247880467917, -242.80790212366,
                                        635.6690019226617, -1685.1426906396948, 4514.487249626413,
                                        -12203.085460039309, 33241.729265522365, -91162.71356536484,
                                        251487.37246667803, -697407.7990546674, 1943046.0695171214};
  stretch_excess = s * estrin(kStretch, s);
  bulge_m = splat<T>(chamber_height_m) * (s * estrin(kBulge, s));
}

/// s^2 = g/3 = P (2 P_o + P) / (3 P_o mu), the series' argument squared, from the gauge pressure: one product chain
/// with the constant 1/(3 P_o mu) (@p inv_three_po_mu) instead of stage 1's two divisions.
template <class T>
inline T stretchSeriesArgumentSquared(T gauge_pa, double atmospheric_pa, double inv_three_po_mu) {
  return gauge_pa * (splat<T>(2.0 * atmospheric_pa) + gauge_pa) * splat<T>(inv_three_po_mu);
}

/// sqrt(h/(L s)) = 1 - s/12 + 29 s^2/96 - ... for s <= 1/20 (scripts/wall_series.py: the terms left out are below 5.1e-19
/// relative), so that stage 4's m = 2 sqrt(h c)/b = (2 sqrt(L c)/b) sqrt(s) sqrt(h/(L s)) needs no square root of h: only
/// sqrt(s), which runs beside the series instead of after them.
template <class T>
inline T bulgeRootSeries(T s) {
  static constexpr double kRoot[19] = {1.0, -0.08333333333333333, 0.3020833333333333, -0.6183449074074074,
                                       1.2755292727623457, -2.845288688753858, 6.709678011503076,
                                       -16.39469503080894, 41.11527568349895, -105.24696972359337,
                                       273.8998798651855, -722.5266941770849, 1927.6122829794456,
                                       -5192.046960708485, 14100.035206253755, -38564.81989420076,
                                       106137.06196593269, -293717.7641003618, 816800.8828791904};
  return estrin(kRoot, s);
}

/// Stage 4's first guess of v = (1 + tan^2 theta)^(1/4) - 1 (docs/MODEL.md; stages.cpp explains the forms), from
/// D = num/den: below D = 1 the [1/1] Pade form of v(D) times the gap's first-order factor (1 - m D/2) where that is
/// positive, written over one division with num and den (D's own division runs beside it, not before it); above, v(D)
/// itself, (D^2)/((r + 1)(sqrt(r) + 1)) with r = sqrt(1 + D^2). A pack computes the second form only when a lane needs it.
template <class T>
inline T quarterPowerStart(T num, T den, T d, T m) {
  const T one = splat<T>(1.0);
  const T num_sq = num * num;
  const T den_sq_pade = den * den + splat<T>(0.375) * num_sq;
  const T shrunk = den - splat<T>(0.5) * m * num;  // den (1 - m D/2)
  const auto shrink = shrunk > splat<T>(0.0);
  const T small_d = (splat<T>(0.25) * num_sq * (shrink ? shrunk : den)) / (den * den_sq_pade);
  const auto below = d < one;
  if (!anyOf(notOf(below))) return small_d;
  const T r = sqrtOf(one + d * d);
  const T large_d = d * d / ((r + one) * (sqrtOf(r) + one));
  return below ? small_d : large_d;
}

/// Stage 4's solve where the walls touch (0 < D <= 1e6, m > 0; the rare rest stays in stages.cpp): safeguarded Halley
/// steps on Q(v) = v (4 + 6v + 4v^2 + v^3) - (D - m v)^2 from @p v (stages.cpp explains Q, the bracket and the stopping
/// rule), then t = D - m v, theta = atan(t), cos theta = 1/w^2 and sin theta = t cos theta, w = 1 + v. Lanes outside
/// @p active take no step, and their outputs mean nothing: the caller selects. Shared by the single evaluation and the
/// batch kernel: a lane stops where the single evaluation stops, and a pack goes on until its last lane has stopped.
/// @return the steps taken (at least 1).
template <class T, class M>
inline int wallHalfAngle(T d, T m, T v, M active, T& rad, T& cos_half, T& sin_half, T& tan_half) {
  const T zero = splat<T>(0.0), one = splat<T>(1.0);
  T lo = zero, hi = d / m;
  v = v < hi ? v : splat<T>(0.5) * hi;
  int steps = 0;
  for (; steps < 64 && anyOf(active); ++steps) {
    const T w = one + v;
    const T tv = d - m * v;
    // Q by Estrin's pairs: v ((4 + 6v) + v^2 (4 + v)).
    const T q = v * ((splat<T>(4.0) + splat<T>(6.0) * v) + (v * v) * (splat<T>(4.0) + v)) - tv * tv;
    active = active & (q != zero);
    const auto above = q > zero;
    hi = active & above ? v : hi;
    lo = active & notOf(above) ? v : lo;
    const T qp = splat<T>(4.0) * w * w * w + splat<T>(2.0) * m * tv;
    const T qpp = splat<T>(12.0) * w * w - splat<T>(2.0) * m * m;
    const T step = splat<T>(2.0) * q * qp / (splat<T>(2.0) * qp * qp - q * qpp);
    T next = v - step;
    const auto halley = (next >= lo) & (next <= hi);
    next = halley ? next : splat<T>(0.5) * (lo + hi);
    const T moved = next - v < zero ? v - next : next - v;
    v = active ? next : v;
    // A Halley step of size s leaves an error of order s^3; t = D - m v needs m * error < ulp(t).
    const T d_mv = d - m * v, v_tiny = v + splat<T>(1e-300);
    const auto converged = halley & (moved * moved * moved * (one + m) <=
                                     splat<T>(1e-17) * (one < d_mv ? one : d_mv) * (one < v_tiny ? one : v_tiny));
    const auto bracketed = hi - lo <= splat<T>(4.0 * __DBL_EPSILON__) * hi;
    active = active & notOf(converged) & notOf(bracketed);
  }
  const T t = d - m * v;
  const T w = one + v;
  tan_half = t;
  rad = atanNonNegative(t);
  cos_half = one / (w * w);  // w is solved to well below an ulp of v: no square root needed
  sin_half = t * cos_half;
  return steps < 1 ? 1 : steps;
}

/// Stages 2-3 of one wall where their series hold (P >= 0 and s = sqrt(g/3) <= kStretchSeriesLimit): the stretch
/// excess, the bulge, and, where the walls touch (h > c), stage 4's m = 2 sqrt(h c)/b from the series too
/// (bulgeRootSeries: no square root of h after the series; else m = 0). Written once for solveWall (stages.cpp) and
/// for the model's evaluation (finger_model.cpp), which inlines it so that nothing passes through memory between the
/// stages.
/// @return false beyond the series' limit (or for P < 0, NaN), where stages.cpp runs the stages one by one
inline bool wallStagesBySeries(double gauge_pa, double atmospheric_pa, double shear_modulus_pa, double chamber_height_m,
                               double gap_m, double two_over_b, double& stretch_excess, double& bulge_m, double& m) {
  const double s_sq =
      stretchSeriesArgumentSquared(gauge_pa, atmospheric_pa, 1.0 / (3.0 * atmospheric_pa * shear_modulus_pa));
  if (!(gauge_pa >= 0.0 && s_sq <= kStretchSeriesLimit * kStretchSeriesLimit)) return false;
  const double s = __builtin_sqrt(s_sq);
  stretchAndBulgeSeries(s, chamber_height_m, stretch_excess, bulge_m);
  m = bulge_m > gap_m
          ? (__builtin_sqrt(chamber_height_m * gap_m) * two_over_b) * (__builtin_sqrt(s) * bulgeRootSeries(s))
          : 0.0;
  return true;
}

/// Stage 4 of one touching wall in its usual form (H = 2h/b < 1e200, m > 0, D <= 1e6): D = H (H - 2k)/(H + m), then
/// wallHalfAngle from quarterPowerStart (stages.cpp, halfAngleOfWall, explains the forms). Shared like
/// wallStagesBySeries.
/// @return false, writing nothing, for the rare forms (no gap, a huge bulge), which halfAngleOfWall takes
inline bool usualWallHalfAngle(double bulge_m, double gap_m, double two_over_b, double m, double& rad,
                               double& cos_half, double& sin_half, double& tan_half, int& iterations) {
  const double big_h = bulge_m * two_over_b;
  // (h c underflows to 0 only for c < 1e-154 m, where m < 1e-75 and dropping it changes nothing.)
  const double num = big_h * ((bulge_m - gap_m) * two_over_b), den = big_h + m;
  const double d = num / den;
  if (!(big_h < 1e200 && m > 0.0 && d <= 1e6)) return false;
  iterations = wallHalfAngle(d, m, quarterPowerStart(num, den, d, m), true, rad, cos_half, sin_half, tan_half);
  return true;
}

}  // namespace
}  // namespace pneumatic_finger
