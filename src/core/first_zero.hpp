// Where a function first falls to zero, and where an increasing one reaches a target: the searches behind the
// membrane's limit point, the supplied volume's limit and volume as an input. Internal header of src/core.
#pragma once

#include <cmath>
#include <limits>

#include "pneumatic_finger/core/golden_section.hpp"

namespace pneumatic_finger {

/// Bisection to the last bit of a sign change of f on [lo, hi] (f(lo) and f(hi) of opposite signs). Returns the end
/// on lo's side.
template <class F>
double bisectSignChange(F&& f, double lo, double hi) {
  const bool lo_positive = f(lo) > 0.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    ((f(mid) > 0.0) == lo_positive ? lo : hi) = mid;
  }
  return lo;
}

/// The first zero of @p f on (start, end), where f is positive at start and, between its samples, falls and rises
/// at most once (a slope's sign: the membrane's dP/dlambda, the supplied volume's dV/ddelta): a coarse scan finds a
/// negative sample or the lowest one, golden-section search the minimum around the lowest, and a negative value is
/// bisected back to the first sign change. +inf where f stays positive. About 200 evaluations, where a scan fine
/// enough to find a narrow dip would take thousands.
template <class F>
double firstFallBelowZero(F&& f, double start, double end) {
  constexpr int kScan = 64;
  const double span = end - start;
  auto at = [&](int i) { return start + span * (static_cast<double>(i) / kScan); };
  int best = 1;
  double best_value = std::numeric_limits<double>::infinity();
  for (int i = 1; i < kScan; ++i) {
    const double v = f(at(i));
    if (v <= 0.0) return bisectSignChange(f, at(i - 1), at(i));
    if (v < best_value) best_value = v, best = i;
  }
  const GoldenMinimum m = goldenSection(f, at(best - 1), at(best + 1), 80,
                                        [](double a, double b, double f1, double f2) {
                                          return f1 > 0.0 && f2 > 0.0 && b - a > 1e-15 * b;
                                        });
  if (m.value > 0.0) return std::numeric_limits<double>::infinity();
  return bisectSignChange(f, at(best - 1), m.x);
}

/// The inverse's cubic Hermite interpolation at @p y between two nodes (x0, y0) and (x1, y1) of an increasing y(x),
/// with dy/dx @p s0 and @p s1 there (dx/dy = 1/s at both): a start within about 1e-5 of the root for Newton's steps
/// on a smooth y; linear where a slope is 0 or infinite (a limit point, a lock) or y1 is infinite.
inline double hermiteInverseStart(double x0, double x1, double y0, double y1, double s0, double s1, double y) {
  const double dy = y1 - y0, t = (y - y0) / dy;
  double x = x0 + t * (x1 - x0);
  if (s0 > 0.0 && s1 > 0.0 && std::isfinite(dy) && std::isfinite(s1)) {
    const double t2 = t * t, t3 = t2 * t;
    x = (2 * t3 - 3 * t2 + 1) * x0 + (t3 - 2 * t2 + t) * dy / s0 + (3 * t2 - 2 * t3) * x1 + (t3 - t2) * dy / s1;
  }
  return x;
}

/// The x in (lo, hi) at which the increasing f reaches @p target, by Newton steps from @p x, with @p fdf(x, f, df)
/// giving f and its derivative together: a step that would leave the bracket (kept from the signs met) bisects it
/// instead. The steps stop when one rounds away, or when a Newton step's error, about (f''/2f') step^2 with f'' from
/// the last two derivatives, is below the last bit: further steps would only dither in f's rounding. From a start
/// within 1e-4 of the root, two or three evaluations; at worst the bisections of the bracket. @p known_x and
/// @p known_df, a point where the derivative is known (a table's node), let the first step's f'' be estimated too
/// (NaN: not known; the first step then always goes on).
template <class FDF>
double increasingNewtonRoot(FDF&& fdf, double target, double lo, double hi, double x,
                            double known_x = std::numeric_limits<double>::quiet_NaN(), double known_df = 0.0) {
  if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
  double prev_x = known_x, prev_df = known_df;
  for (int k = 0; k < 2200; ++k) {  // 1100 bisections span every double
    double f = 0.0, df = 0.0;
    fdf(x, f, df);
    if (f == target) return x;
    (f < target ? lo : hi) = x;
    double next = x - (f - target) / df;
    if (std::fabs(next - x) <= 2e-16 * std::fabs(x)) return x;  // the step rounds away: x is the root to the last bit
    const bool newton = next > lo && next < hi;
    if (!newton) next = 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) return x;  // lo and hi are neighbours
    const double step = std::fabs(next - x);
    // (f''/2f') step^2 <= 1e-17 |next|, f'' ~ (df - prev_df)/(x - prev_x), multiplied out: no division on the path
    // every step waits on.
    const bool known = !std::isnan(prev_x) && prev_x != x;
    if (newton && known &&
        std::fabs(df - prev_df) * (step * step) <= 1e-17 * std::fabs(next) * (std::fabs(x - prev_x) * (2.0 * df))) {
      return next;
    }
    prev_x = x;
    prev_df = df;
    x = next;
  }
  return x;
}

/// The x in [lo, hi] at which the increasing @p f reaches @p target, f(lo) <= target <= f(hi): regula falsi with
/// the Illinois halving (superlinear on a smooth f), and a bisection whenever a step would not shrink the bracket
/// by half within two steps, so that it ends, at the latest, when lo and hi are neighbouring doubles. Returns the end
/// whose f is nearer the target.
template <class F>
double increasingRoot(F&& f, double target, double lo, double hi) {
  double g_lo = f(lo) - target, g_hi = f(hi) - target;
  if (!(g_lo < 0.0)) return lo;
  if (!(g_hi > 0.0)) return hi;
  double true_lo = g_lo, true_hi = g_hi;  // g_lo and g_hi are the Illinois-weighted ones
  int side = 0;
  double width_before = hi - lo;
  for (int i = 0; i < 2200; ++i) {  // 1100 bisections span every double
    double x = lo - g_lo * (hi - lo) / (g_hi - g_lo);
    // Every second step checks that the last two halved the bracket; otherwise this one bisects.
    if (i % 2 == 1) {
      if (hi - lo > 0.5 * width_before) x = 0.5 * (lo + hi);
      width_before = hi - lo;
    }
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    if (!(x > lo && x < hi)) break;  // lo and hi are neighbours
    const double g = f(x) - target;
    if (g == 0.0) return x;
    if (g < 0.0) {
      lo = x, g_lo = true_lo = g;
      if (side == -1) g_hi *= 0.5;
      side = -1;
    } else {
      hi = x, g_hi = true_hi = g;
      if (side == 1) g_lo *= 0.5;
      side = 1;
    }
  }
  return -true_lo <= true_hi ? lo : hi;
}

}  // namespace pneumatic_finger
