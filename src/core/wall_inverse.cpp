// The rising branch's inverse, built (docs/MODEL.md, "The wall's inverse"; wall_inverse.hpp has the evaluation).
#include "wall_inverse.hpp"

#include <cmath>
#include <limits>

#include "pneumatic_finger/core/units.hpp"
#include "thick_wall.hpp"

namespace pneumatic_finger {

namespace {

constexpr int kTerms = MembraneWall::kInverseCoefficients;
// The check: delta within this share of itself, plus the root's own spread where P is flat: the law's pressure is
// rounded within a few eps P, which moves the root by eps P / (dP/ddelta) each (the Newton steps' root as much as
// the inverse's; near the limit point, where dP/ddelta vanishes, it dominates).
constexpr double kRelativeTolerance = 4e-15;
constexpr double kPressureRoundings = 16.0;
// A wall that rises to its lock: the inverse's share of the lock's stretch (its pressure there is a few times the
// pressure halfway; above it, the Newton steps).
constexpr double kLockShare = 0.8;
constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

// The pressure at @p position (s K) among the wall's pieces: P = top (1 - s^2).
double gaugeAtPosition(const MembraneWall& w, double position) {
  const double s = position / w.inverse_pieces;
  return w.inverse_top_gauge_pa * (1.0 - s * s);
}

// sum a_k T_k(x) as sum c_k x^k, by T_{k+1} = 2 x T_k - T_{k-1}.
void chebyshevToMonomial(const double (&a)[kTerms], double* c) {
  double before[kTerms] = {1.0}, now[kTerms] = {0.0, 1.0}, next[kTerms];
  for (int i = 0; i < kTerms; ++i) c[i] = a[0] * before[i] + a[1] * now[i];
  for (int k = 2; k < kTerms; ++k) {
    for (int i = 0; i < kTerms; ++i) next[i] = (i > 0 ? 2.0 * now[i - 1] : 0.0) - before[i];
    for (int i = 0; i < kTerms; ++i) {
      before[i] = now[i];
      now[i] = next[i];
      c[i] += a[k] * now[i];
    }
  }
}

// The piece's row of coefficients.
double* pieceRow(MembraneWall& w, int piece) {
  const auto stride = static_cast<std::size_t>(w.inverse_functions) * kTerms;
  return &w.inverse_coefficients[static_cast<std::size_t>(piece) * stride];
}

// g = delta / q (and g_b = delta_b / q) at the piece's Chebyshev nodes (the law's own roots), interpolated, into
// the piece's row. false where a node has no root.
bool fitPiece(MembraneWall& w, int piece) {
  double a[2][kTerms] = {};
  for (int j = 0; j < kTerms; ++j) {
    const double angle = kPi * (j + 0.5) / kTerms;
    const double p = gaugeAtPosition(w, piece + 0.5 * (std::cos(angle) + 1.0));
    const double q = p * w.inverse_scale_per_pa, delta = membraneNewtonStretchExcess(w, p);
    const double g[2] = {delta / q, w.inverse_functions == 2 ? thickOuterStretchExcess(w, delta) / q : 0.0};
    if (!std::isfinite(g[0]) || !std::isfinite(g[1])) return false;
    for (int f = 0; f < w.inverse_functions; ++f) {
      for (int k = 0; k < kTerms; ++k) a[f][k] += (k == 0 ? 1.0 : 2.0) / kTerms * g[f] * std::cos(k * angle);
    }
  }
  for (int f = 0; f < w.inverse_functions; ++f) chebyshevToMonomial(a[f], pieceRow(w, piece) + f * kTerms);
  return true;
}

// The inverse against the law's root at the piece's Chebyshev extrema (between the nodes, where the interpolation
// errs most, and its ends), as the evaluation computes it: from the pressure.
// The outer face's stretch is checked likewise, its spread the root's times d delta_b / d delta.
bool pieceHolds(const MembraneWall& w, int piece) {
  for (int m = 0; m <= kTerms; ++m) {
    const double p = gaugeAtPosition(w, piece + 0.5 * (1.0 - std::cos(kPi * m / kTerms)));
    if (!(p > 0.0) || !(p < w.limit_gauge_pa)) continue;  // rest (0 exactly) and the limit (refused)
    const double delta = membraneNewtonStretchExcess(w, p);
    double gauge_pa = 0.0, slope_pa = 0.0;
    membraneGaugeAndSlope(w, delta, gauge_pa, slope_pa);
    const double spread = kPressureRoundings * kEpsilon * p / slope_pa;
    double outer = 0.0;
    const double inverse = risingInverse(w, p, w.inverse_functions == 2 ? &outer : nullptr);
    if (!(std::fabs(inverse - delta) <= kRelativeTolerance * delta + spread)) return false;
    if (w.inverse_functions == 1) continue;
    const double delta_b = thickOuterStretchExcess(w, delta), la = 1.0 + delta, lb = 1.0 + delta_b;
    const double outer_spread = spread * w.inner_outer_volume_ratio * la * la / (lb * lb);
    if (!(std::fabs(outer - delta_b) <= kRelativeTolerance * delta_b + outer_spread)) return false;
  }
  return true;
}

// At rest g is exactly top / (dP/ddelta at 0): the last piece is shifted to end there, so that the smallest pressures
// keep delta's digits as the Newton steps do (the interpolation alone is off by a few 1e-15 there).
// The outer face's g_b likewise, times d delta_b / d delta at rest, (A/B)^3.
void pinRest(MembraneWall& w) {
  double gauge_pa = 0.0, slope_pa = 0.0;
  membraneGaugeAndSlope(w, 0.0, gauge_pa, slope_pa);
  const double at_rest[2] = {w.inverse_top_gauge_pa / slope_pa,
                             w.inverse_top_gauge_pa / slope_pa * w.inner_outer_volume_ratio};
  for (int f = 0; f < w.inverse_functions; ++f) {
    double* last = pieceRow(w, w.inverse_pieces - 1) + f * kTerms;
    double c[kTerms];
    for (int j = 0; j < kTerms; ++j) c[j] = last[j];
    last[0] += at_rest[f] - inversePolynomial(c, 1.0);
  }
}

// Every piece fitted, then every piece checked (a piece's end is its neighbour's start).
bool fitAndCheck(MembraneWall& w, int pieces) {
  w.inverse_pieces = pieces;
  w.inverse_coefficients.assign(static_cast<std::size_t>(pieces * w.inverse_functions) * kTerms, 0.0);
  for (int piece = 0; piece < pieces; ++piece) {
    if (!fitPiece(w, piece)) return false;
  }
  pinRest(w);
  for (int piece = 0; piece < pieces; ++piece) {
    if (!pieceHolds(w, piece)) return false;
  }
  return true;
}

}  // namespace

void buildRisingInverse(MembraneWall& w) {
  w.inverse_pieces = 0;
  w.inverse_coefficients.clear();
  if (!w.has_guess) return;
  // Up to the limit point; a wall that rises to its lock, up to kLockShare of the lock's stretch (the pressure grows
  // without bound towards the lock, where no polynomial follows it).
  const double top = std::isfinite(w.limit_gauge_pa)
                         ? w.limit_gauge_pa
                         : membraneGaugeForStretchExcess(w, kLockShare * w.locking_stretch_excess);
  if (!(top > 0.0) || !std::isfinite(top)) return;
  w.inverse_top_gauge_pa = top;
  w.inverse_scale_per_pa = 1.0 / top;
  w.inverse_functions = w.outer_face_bends ? 2 : 1;
  for (int pieces = 4; pieces <= MembraneWall::kInverseMaxPieces; pieces *= 2) {
    if (fitAndCheck(w, pieces)) return;
  }
  w.inverse_pieces = 0;
  w.inverse_coefficients.clear();
}

}  // namespace pneumatic_finger
