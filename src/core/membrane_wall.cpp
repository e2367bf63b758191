#include "pneumatic_finger/core/membrane_wall.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pneumatic_finger/core/units.hpp"
#include "first_zero.hpp"
#include "membrane_law.hpp"
#include "thick_wall.hpp"
#include "wall_inverse.hpp"

namespace pneumatic_finger {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The sign of d P / d lambda, times positive factors: (J_m - e)(7 - lambda^6) lambda^4 + 4 (lambda^6 - 1)^2 for a
// Gent wall (the log slope times lambda (lambda^6 - 1) lambda^4 (J_m - e)); 7 - lambda^6 for a Neo-Hookean one.
double slopeSign(const MembraneWall& w, double d) {
  if (w.thick) return thickGaugeSlope(w, d);
  const double lam = 1.0 + d, u = sixthPowerMinusOne(d);
  if (w.locking_jm == 0.0) return 6.0 - u;
  const double lam4 = lam * lam * lam * lam;
  return (w.locking_jm - firstInvariantExcess(d)) * (6.0 - u) * lam4 + 4.0 * u * u;
}

// The Gent wall's limit point: the first zero of slopeSign beyond the Neo-Hookean one (7^(1/6) - 1), where the first
// term turns negative; the locking term grows without bound towards the lock, so a zero exists only where the first
// term wins somewhere. Between the two, slopeSign falls and then rises (one product that grows from 0 and returns to 0
// at the lock, plus a rising square): a coarse scan finds its lowest sample, golden-section search its minimum, and a
// negative minimum is bisected back to the first sign change. A calibration builds thousands of models: this costs
// about 200 evaluations, where a fine scan would cost thousands.
double gentLimitStretchExcess(const MembraneWall& w) {
  const double start = std::pow(7.0, 1.0 / 6.0) - 1.0;
  if (!(w.locking_stretch_excess > start)) return kInf;
  return firstFallBelowZero([&w](double x) { return slopeSign(w, x); }, start, w.locking_stretch_excess);
}

// The thin membrane's P and dP/ddelta (membrane_law.hpp, shared with the batch's packs).
void thinGaugeAndSlope(const MembraneWall& w, double d, double& gauge_pa, double& slope_pa) {
  thinGaugeAndSlopeOf(w.pressure_scale_pa, w.locking_jm, d, gauge_pa, slope_pa);
}

// The starting table (MembraneWall::guess_*): Chebyshev-Lobatto nodes delta_i = top (1 - cos(pi i/n))/2 on [0, top],
// close together at both ends: near rest, where P bends from its first slope, and near the limit point or the lock.
void buildGuess(MembraneWall& w) {
  const double top = std::isfinite(w.limit_stretch_excess) ? w.limit_stretch_excess : w.locking_stretch_excess;
  if (!std::isfinite(top)) return;
  constexpr int n = MembraneWall::kGuessNodes;
  for (int i = 0; i <= n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    w.guess_stretch_excess[k] = i == n ? top : 0.5 * top * (1.0 - std::cos(kPi * i / n));
    membraneGaugeAndSlope(w, w.guess_stretch_excess[k], w.guess_gauge_pa[k], w.guess_slope_pa[k]);
  }
  w.guess_gauge_pa[static_cast<std::size_t>(n)] = std::isfinite(w.limit_stretch_excess) ? w.limit_gauge_pa : kInf;
  w.has_guess = true;
}

}  // namespace

MembraneWall membraneWall(double shear_modulus_pa, double wall_thickness_m, double chamber_height_m,
                          double locking_jm, bool thick, bool outer_face_bends, double bulge_share) {
  MembraneWall w;
  w.chamber_height_m = chamber_height_m;
  w.thick = thick;
  w.outer_face_bends = thick && outer_face_bends;
  w.pressure_scale_pa = thick ? shear_modulus_pa : 4.0 * shear_modulus_pa * wall_thickness_m / chamber_height_m;
  if (thick) {
    w.outer_inner_ratio = 1.0 + 2.0 * wall_thickness_m / chamber_height_m;  // B/A, A = L/2
    w.inner_outer_volume_ratio = 1.0 / (w.outer_inner_ratio * w.outer_inner_ratio * w.outer_inner_ratio);
  }
  w.decay_scale_pa = thick ? 4.0 * shear_modulus_pa * w.outer_inner_ratio : w.pressure_scale_pa;
  w.bulge_per_stretch_m = (w.outer_face_bends ? 0.5 * chamber_height_m * w.outer_inner_ratio : 0.5 * chamber_height_m) *
                          bulge_share;
  w.locking_jm = locking_jm;
  w.locking_stretch_excess = kInf;
  if (locking_jm > 0.0) {
    // I1 - 3 rises monotonically from 0 (delta = 0) without bound: bracket its crossing of J_m, then bisect.
    double hi = 1.0;
    while (firstInvariantExcess(hi) < locking_jm) hi *= 2.0;
    w.locking_stretch_excess =
        bisectSignChange([locking_jm](double d) { return firstInvariantExcess(d) - locking_jm; }, 0.0, hi);
    if (thick) setThickGentRoots(w);
  }
  if (thick) {
    // No closed form: the first fall of dP/ddelta below zero, from rest to the lock (a Neo-Hookean thick wall's
    // maximum comes later the thicker the wall; past delta = 100 a wall would have burst long before).
    const double end = std::isfinite(w.locking_stretch_excess) ? w.locking_stretch_excess : 100.0;
    w.limit_stretch_excess = firstFallBelowZero([&w](double x) { return slopeSign(w, x); }, 1e-9, end);
  } else {
    w.limit_stretch_excess = locking_jm == 0.0 ? std::pow(7.0, 1.0 / 6.0) - 1.0 : gentLimitStretchExcess(w);
  }
  w.limit_gauge_pa = std::isfinite(w.limit_stretch_excess)
                         ? membraneGaugeForStretchExcess(w, w.limit_stretch_excess)
                         : kInf;
  w.far_turning_stretch_excess = w.far_turning_gauge_pa = kInf;
  if (std::isfinite(w.limit_stretch_excess) && std::isfinite(w.locking_stretch_excess)) {
    // Past the limit slopeSign is negative (the limit is its last positive point), and towards the lock the locking
    // term makes it positive again: halving the distance to the lock finds a positive point, and the last negative
    // one before it brackets the minimum, which bisection finds.
    const auto sign = [&w](double x) { return slopeSign(w, x); };
    double negative = std::nextafter(w.limit_stretch_excess, kInf), positive = negative;
    for (int i = 0; i < 200 && !(sign(positive) > 0.0); ++i) {
      negative = positive;
      positive = 0.5 * (positive + w.locking_stretch_excess);
    }
    if (sign(positive) > 0.0 && !(sign(negative) > 0.0)) {
      // bisectSignChange returns the end on its first argument's side: the last negative point, the minimum.
      w.far_turning_stretch_excess = bisectSignChange(sign, negative, positive);
      w.far_turning_gauge_pa = membraneGaugeForStretchExcess(w, w.far_turning_stretch_excess);
    }
  }
  w.snap_stretch_excess = w.snap_gauge_pa = std::numeric_limits<double>::quiet_NaN();  // setSnapPoint, when asked
  buildGuess(w);
  return w;
}

double membraneGaugeForStretchExcess(const MembraneWall& w, double d) {
  if (w.thick) return thickGaugeForStretchExcess(w, d);
  const double lam = 1.0 + d, lam2 = lam * lam, lam7 = lam2 * lam2 * lam2 * lam;
  const double neo_hookean = w.pressure_scale_pa * (sixthPowerMinusOne(d) / lam7);
  if (w.locking_jm == 0.0) return neo_hookean;
  const double room = w.locking_jm - firstInvariantExcess(d);
  return room > 0.0 ? neo_hookean * (w.locking_jm / room) : kInf;
}

void membraneGaugeAndSlope(const MembraneWall& w, double delta, double& gauge_pa, double& slope_pa) {
  if (!w.thick) return thinGaugeAndSlope(w, delta, gauge_pa, slope_pa);
  thickGaugeAndSlope(w, delta, gauge_pa, slope_pa);
}

namespace {

// The stretch excess where P = gauge_pa on a rising part of the law, bracketed by (lo, hi), from @p start: Newton
// steps on P with P and dP/ddelta together (increasingNewtonRoot); @p known_delta and @p known_slope_pa as there.
double risingStretchExcess(const MembraneWall& w, double gauge_pa, double lo, double hi, double start,
                           double known_delta = std::numeric_limits<double>::quiet_NaN(), double known_slope_pa = 0.0) {
  return increasingNewtonRoot([&w](double x, double& g, double& slope) { membraneGaugeAndSlope(w, x, g, slope); },
                              gauge_pa, lo, hi, start, known_delta, known_slope_pa);
}

// The rising branch from the wall's table: the node interval that holds @p gauge_pa brackets the root, and
// the inverse's cubic Hermite interpolation there (d delta/dP = 1/slope at both nodes; linear where a node's slope
// is 0 or infinite: the limit point, the lock) starts the Newton steps within 1e-5 or so of the root, so that two
// or three steps reach it.
double tabulatedStretchExcess(const MembraneWall& w, double gauge_pa) {
  const auto& p = w.guess_gauge_pa;
  const auto i = static_cast<std::size_t>(std::upper_bound(p.begin(), p.end(), gauge_pa) - p.begin()) - 1;
  const double s0 = w.guess_slope_pa[i], lo = w.guess_stretch_excess[i], hi = w.guess_stretch_excess[i + 1];
  const double d = hermiteInverseStart(lo, hi, p[i], p[i + 1], s0, w.guess_slope_pa[i + 1], gauge_pa);
  return risingStretchExcess(w, gauge_pa, lo, hi, d, lo, s0);
}

}  // namespace

double membraneStretchExcess(const MembraneWall& w, double gauge_pa) {
  if (inverseCovers(w, gauge_pa)) return risingInverse(w, gauge_pa);
  return membraneNewtonStretchExcess(w, gauge_pa);
}

double membraneNewtonStretchExcess(const MembraneWall& w, double gauge_pa) {
  if (!(gauge_pa >= 0.0) || !(gauge_pa < w.limit_gauge_pa)) return std::numeric_limits<double>::quiet_NaN();
  if (gauge_pa == 0.0) return 0.0;
  if (w.has_guess) return tabulatedStretchExcess(w, gauge_pa);
  // No table: P rises without a limit or a lock (a thick Neo-Hookean wall whose maximum, if any, lies beyond the
  // search's end). Bracket the root by doubling, then the same Newton steps.
  double hi = 1.0;
  for (int i = 0; i < 64 && membraneGaugeForStretchExcess(w, hi) < gauge_pa; ++i) hi *= 2.0;
  return risingStretchExcess(w, gauge_pa, 0.0, hi, 0.5 * hi);
}

double membraneFarStretchExcess(const MembraneWall& w, double gauge_pa) {
  if (!(gauge_pa > w.far_turning_gauge_pa) || !std::isfinite(w.far_turning_gauge_pa) || !std::isfinite(gauge_pa)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const double lo = w.far_turning_stretch_excess, hi = w.locking_stretch_excess;
  return risingStretchExcess(w, gauge_pa, lo, hi, 0.5 * (lo + hi));
}

WallSolution solveMembraneWall(const MembraneWall& w, double gauge_pa, double gap_m, double wall_critical_height_m) {
  WallSolution s;
  if (w.outer_face_bends && inverseCovers(w, gauge_pa)) {
    // The inverse gives the outer face's stretch too: no cube root.
    double outer_stretch_excess = 0.0;
    s.stretch_excess = risingInverse(w, gauge_pa, &outer_stretch_excess);
    s.bulge_m = outerFaceBulgeM(w, outer_stretch_excess);
    s.half = halfAngle(s.bulge_m, gap_m, wall_critical_height_m);
    return s;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double delta = membraneStretchExcess(w, gauge_pa < 0.0 ? 0.0 : gauge_pa);
  if (std::isnan(delta)) {
    s.stretch_excess = s.bulge_m = nan;
    s.half.rad = s.half.cos = s.half.sin = s.half.tan = nan;
    return s;
  }
  return membraneWallAtStretch(w, delta, gap_m, wall_critical_height_m);
}

WallSolution membraneWallAtStretch(const MembraneWall& w, double delta, double gap_m, double wall_critical_height_m) {
  WallSolution s;
  s.stretch_excess = delta;
  s.bulge_m = membraneBulgeM(w, delta);
  s.half = halfAngle(s.bulge_m, gap_m, wall_critical_height_m);
  return s;
}

double membraneGaugeForBulge(const MembraneWall& w, double bulge_m) {
  if (!(bulge_m > 0.0)) return 0.0;
  const double delta = membraneStretchForBulge(w, bulge_m);
  const double top = std::isfinite(w.limit_stretch_excess) ? w.limit_stretch_excess : w.locking_stretch_excess;
  if (!(delta < top)) return std::numeric_limits<double>::quiet_NaN();
  return membraneGaugeForStretchExcess(w, delta);
}

double membraneBulgeM(const MembraneWall& w, double delta) {
  if (!w.outer_face_bends) return w.bulge_per_stretch_m * delta;
  return outerFaceBulgeM(w, thickOuterStretchExcess(w, delta));
}

double membraneStretchForBulge(const MembraneWall& w, double bulge_m) {
  if (!w.outer_face_bends) return bulge_m / w.bulge_per_stretch_m;
  // The outer face's stretch excess, then lambda_a^3 - 1 = (lambda_b^3 - 1) (B/A)^3.
  const double db = bulge_m / w.bulge_per_stretch_m;
  const double ub = db * (3.0 + db * (3.0 + db));
  return std::expm1(std::log1p(ub / w.inner_outer_volume_ratio) / 3.0);
}

}  // namespace pneumatic_finger
