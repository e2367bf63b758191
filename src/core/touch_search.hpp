// The contact rule's one touch search (contact.cpp): along a variable x that closes the finger monotonically, the
// first x at which a moving segment of the backbone touches the obstacle. What x is, and how a shape is placed at x,
// is the Sampler's: the free walls' half angle for identical chambers with the robust solver (one sincos per sample,
// with a bound on how fast a point moves, so far obstacles are passed in long steps), or the square root of the
// pressure otherwise (the model solved per sample, in fixed steps). Internal header of src/core.
//
// A Sampler has:
//   int first, n;                 the moving segments are first..n (segment k: O_k -> O_{k+1})
//   double step;                  the grid of x on which the samples lie
//   double speed;                 a bound on |d clearance / dx| (m per unit of x); infinity when there is none
//   double x_cap;                 no skip goes past it (the variable's own range)
//   std::array<double, kMaxChamberCount + 1> per_segment;
//   double clearance(double x, int from, int to, int& segment, bool each);
//                                 the smallest clearance of segments from..to at x and which segment has it (the
//                                 shape is placed for every moving segment); with each, every one's into per_segment
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "pneumatic_finger/core/golden_section.hpp"

namespace pneumatic_finger {

/// Segments this close (m) at a touch are touching too; a grazing approach that comes this close is a touch.
constexpr double kTouchDistanceM = 1e-12;

/// The touch is found to this relative precision in the search variable (the angles follow to about 1e-14 rad).
constexpr double kTouchRelativeTolerance = 1e-15;

/// The longest any iterative step of the search may run (it ends far sooner; this only bounds a pathological case).
constexpr int kTouchMaxIterations = 200;

/// Where the bracketing stopped: a touch in [lo, hi] (lo clear, hi touching; lo == hi for a grazing touch), or clear
/// up to @p clear, at or past the end asked for.
struct TouchBracket {
  bool found = false;
  double lo = 0.0, hi = 0.0, clear = 0.0;
};

/// A grazing approach between the samples a, m, b (c(m) below both): the minimum by golden sections, which stop as soon
/// as the speed bound proves the minimum stays clear of kTouchDistanceM. A touch when it comes that close.
template <class Sampler>
bool grazingTouch(Sampler& s, double a, double b, double& x_touch) {
  int segment = 0;
  const GoldenMinimum m = goldenSection(
      [&s, &segment](double x) { return s.clearance(x, s.first, s.n, segment, false); }, a, b, kTouchMaxIterations,
      [&s](double a_, double b_, double f1, double f2) {
        return b_ - a_ > 1e-16 * b_ && std::min(f1, f2) - s.speed * (b_ - a_) <= kTouchDistanceM;
      });
  x_touch = m.x;
  return m.value <= kTouchDistanceM;
}

/// Samples from @p x0 on the grid x0 + j step until a touch or @p x_end. Far from the obstacle, whole runs of the grid
/// are skipped as the speed bound allows (never past a point where the clearance could have come within
/// kTouchDistanceM). The samples depend on the obstacle and the start alone, not on the end asked for: the touch
/// found is the same whatever the end.
template <class Sampler>
TouchBracket bracketTouch(Sampler& s, double x0, double x_end) {
  TouchBracket out;
  int segment = 0;
  std::array<double, 3> x{x0, x0, x0};
  std::array<double, 3> c{INFINITY, INFINITY, s.clearance(x0, s.first, s.n, segment, false)};
  for (long j = 0;;) {
    const double skip = std::isfinite(s.speed) ? (c[2] - kTouchDistanceM) / s.speed : 0.0;
    const double allowed = std::min(skip, s.x_cap - (x0 + static_cast<double>(j) * s.step));
    j += std::max(1L, static_cast<long>(std::floor(allowed / s.step)));
    const double xj = x0 + static_cast<double>(j) * s.step;
    x = {x[1], x[2], xj};
    c = {c[1], c[2], s.clearance(xj, s.first, s.n, segment, false)};
    if (c[2] <= 0) {
      out.found = true;
      out.lo = x[1];
      out.hi = xj;
      return out;
    }
    if (c[1] < c[0] && c[1] < c[2] && grazingTouch(s, x[0], x[2], out.lo)) {
      out.found = true;
      out.hi = out.lo;
      return out;
    }
    if (xj >= x_end) {
      out.clear = xj;
      return out;
    }
  }
}

/// Narrows a bracketed touch to kTouchRelativeTolerance: regula falsi with the Illinois correction (the clearance is
/// smooth near a touch, so a few steps do), bisection when a step leaves the bracket. Only the segments that can come
/// within reach inside the bracket (by the speed bound) are measured: usually one or two.
template <class Sampler>
void refineTouch(Sampler& s, TouchBracket& b) {
  if (!(b.hi > b.lo)) return;  // a grazing touch is a point already
  int segment = 0, first = s.n, last = s.first;
  double f_lo = s.clearance(b.lo, s.first, s.n, segment, true);
  for (int k = s.first; k <= s.n; ++k) {
    if (s.per_segment[static_cast<std::size_t>(k)] - s.speed * (b.hi - b.lo) <= kTouchDistanceM) {
      first = std::min(first, k);
      last = std::max(last, k);
    }
  }
  first = std::min(first, last);
  double f_hi = s.clearance(b.hi, first, last, segment, false);
  int side = 0;
  for (int it = 0; it < kTouchMaxIterations && b.hi - b.lo > kTouchRelativeTolerance * b.hi; ++it) {
    double mid = (b.lo * f_hi - b.hi * f_lo) / (f_hi - f_lo);
    if (!(mid > b.lo && mid < b.hi)) mid = 0.5 * (b.lo + b.hi);
    const double f = s.clearance(mid, first, last, segment, false);
    if (f <= 0) {
      b.hi = mid, f_hi = f;
      if (side == -1) f_lo *= 0.5;  // the same end kept twice: halve its weight, or the secant crawls
      side = -1;
    } else {
      b.lo = mid, f_lo = f;
      if (side == 1) f_hi *= 0.5;
      side = 1;
    }
  }
}

}  // namespace pneumatic_finger
