#include "pneumatic_finger/core/stages.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pneumatic_finger/core/units.hpp"
#include "wall_chain.hpp"

namespace pneumatic_finger {

namespace {

// Above this tan(theta), 1 + t^2 == t^2 in double, and t^2 would overflow near 1e154: switch to the
// asymptotic forms (1 + t^2)^(1/4) = sqrt(t), cos = 1/t, which are then exact to rounding.
constexpr double kLargeTan = 1e8;

// (1 + t^2)^(1/4) - 1 without cancellation near t = 0, and (1 + t^2)^(1/4) itself.
struct QuarterPower {
  double w;      // (1 + t^2)^(1/4)
  double w_m1;   // w - 1
};

inline QuarterPower quarterPower(double t) {
  if (t > kLargeTan) {
    const double w = std::sqrt(t);
    return {w, w - 1.0};
  }
  const double r = std::sqrt(1.0 + t * t);
  const double w = std::sqrt(r);
  // w - 1 = (r - 1)/(w + 1) = t^2 / ((r + 1)(w + 1))
  return {w, t * t / ((r + 1.0) * (w + 1.0))};
}

}  // namespace

double energyGroup(double gauge_pa, double atmospheric_pa, double shear_modulus_pa) {
  if (!(gauge_pa > 0.0)) return 0.0;  // also NaN; callers refuse NaN before this
  // (P/P_o)(2 P_o + P)/mu: each factor is O(1) for sane inputs, and the product form avoids
  // ((P_abs/P_o)^2 - 1), which cancels for small P.
  const double g = energyGroupProduct(gauge_pa, atmospheric_pa, shear_modulus_pa);
  return g < kMaxEnergyGroup ? g : kMaxEnergyGroup;
}

namespace {

// delta for very large g, where Halley's products (F'^2 ~ g^2) would overflow: Newton on the fixed point
// delta = R(delta) = sqrt(g (1 + delta)/(3 + delta)), whose terms are all positive and O(g) at most.
// R' = R/((1 + delta)(3 + delta)) lies in [0, 0.134], so the iteration converges from any start.
double stretchExcessLarge(double g, double delta) {
  for (int i = 0; i < 32; ++i) {
    const double one_p = 1.0 + delta;
    const double three_p = 3.0 + delta;
    const double r = std::sqrt(g * (one_p / three_p));
    const double step = (delta - r) / (1.0 - r / (one_p * three_p));
    delta -= step;
    if (std::fabs(step) <= 1e-10 * delta) break;  // quadratic: the next step would be below one ulp
  }
  return delta;
}

}  // namespace

double stretchExcess(double g) {
  if (!(g > 0.0)) return 0.0;
  double delta = stretchExcessFirstGuess(g);
  if (g > kStretchHalleyMaxEnergyGroup) return stretchExcessLarge(g, delta);
  for (int i = 0; i < 16; ++i) {
    const double step = stretchExcessHalleyStep(g, delta);
    delta -= step;
    if (!(std::fabs(step) > kStretchHalleyStop * delta)) break;
  }
  return delta;
}

double bulge(double stretch_excess, double chamber_height_m) { return bulgeOf(stretch_excess, chamber_height_m); }

namespace {

// tan(theta) for a very large bulge (D > 1e6), where the polynomial below would overflow (v^4 ~ t^2): safeguarded
// Newton on f(t) = t + m (w(t) - 1) - D in t itself. f is increasing, with its root in [D - m (w(D) - 1), D]; w uses
// its overflow-free asymptotic form.
double tanHalfAngleLargeBulge(double d, double m, int& iterations) {
  double lo = 0.0, hi = d;
  double t = d - m * quarterPower(d).w_m1;
  if (t > lo) lo = t; else t = 0.5 * hi;
  for (; iterations < 64; ++iterations) {
    const QuarterPower q = quarterPower(t);
    const double f = t + m * q.w_m1 - d;
    if (f == 0.0) break;
    (f > 0.0 ? hi : lo) = t;
    double next = t - f / (1.0 + 0.5 * m * t / (q.w * q.w * q.w));
    const bool newton = next >= lo && next <= hi;
    if (!newton) next = 0.5 * (lo + hi);
    const double step = next - t;
    t = next;
    if (newton && std::fabs(step) <= 1e-10 * t) break;  // quadratic: the next step is below one ulp
    if (hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * hi) break;
  }
  ++iterations;
  return t;
}

// theta, cos and sin from t = tan(theta) for the rare forms (no gap, a huge bulge); the usual ones come with w.
HalfAngle halfAngleFromTan(double t, int iterations) {
  HalfAngle out;
  out.iterations = iterations;
  out.tan = t;
  out.rad = atanNonNegative(t);  // our own atan (simd_math.hpp), as everywhere in the chain
  if (t > kLargeTan) {
    out.cos = 1.0 / t;
    out.sin = 1.0;
  } else {
    out.cos = 1.0 / std::sqrt(1.0 + t * t);
    out.sin = t * out.cos;
  }
  return out;
}

// Stage 4 with the walls touching, from the bulge and m = 2 sqrt(h c)/b (the caller's: from h itself, or from the
// series in s). Eq 15 <=> t + m (w - 1) = D, with t = tan(theta), w = (1 + t^2)^(1/4) and D = H - m, formed as
// H (H - 2k)/(H + m) so that it keeps its digits where h -> c (both H and m -> 2k). The usual bulges go through the
// solve shared with the batch kernel (wall_chain.hpp, wallHalfAngle): v = w - 1 as the root of
//   Q(v) = v (4 + 6v + 4v^2 + v^3) - (D - m v)^2 = 0,
// written so that nothing cancels near v = 0; Q is increasing on [0, D/m] (Q' = 4 w^3 + 2 m t > 0), negative at 0 and
// positive at D/m, so it has one root there, found by safeguarded Halley steps: no square root per step. The start
// (quarterPowerStart) is near v(D) = (1 + D^2)^(1/4) - 1, an upper bound (t <= D): for D < 1 its [1/1] Pade form
// (x/4)/(1 + 3x/8), x = D^2, is within 1e-6 relative at D = 0.1 and costs no square root. The root's t = D - m v is
// below D, and to first order v(t) = v(D) (1 - m v'(D)) with v'(D) = D/(2 w^3), about D/2: that factor takes the
// start from a relative error of m D/2 (2e-3 at the validated range's top) to one of order (m D)^2 (2e-5 there), close
// enough for one Halley step. A step of size s leaves an error of order s^3; t needs m * error < ulp(t).
HalfAngle halfAngleOfWall(double bulge_m, double gap_m, double two_over_b, double m) {
  HalfAngle out;
  if (usualWallHalfAngle(bulge_m, gap_m, two_over_b, m, out.rad, out.cos, out.sin, out.tan, out.iterations)) return out;
  // The rare forms.
  const double big_h = bulge_m * two_over_b;
  if (!(big_h < 1e200)) {  // tan(theta) ~ H > 1e200: theta = pi/2 to the last bit
    out.rad = kHalfPi;
    out.cos = 0.0;
    out.sin = 1.0;
    out.tan = std::numeric_limits<double>::infinity();
    return out;
  }
  const double d = big_h * ((bulge_m - gap_m) * two_over_b) / (big_h + m);
  int iterations = 0;
  if (!(m > 0.0)) return halfAngleFromTan(d, iterations);  // c = 0: eq 15 is h = (b/2) tan(theta)
  return halfAngleFromTan(tanHalfAngleLargeBulge(d, m, iterations), iterations);  // D > 1e6
}

}  // namespace

HalfAngle halfAngle(double bulge_m, double gap_m, double wall_critical_height_m) {
  if (!(bulge_m > gap_m)) return HalfAngle{};  // walls not in contact (docs/MODEL.md, stage 4)
  const double two_over_b = 2.0 / wall_critical_height_m;
  return halfAngleOfWall(bulge_m, gap_m, two_over_b, std::sqrt(bulge_m * gap_m) * two_over_b);
}

WallSolution solveWall(double gauge_pa, double atmospheric_pa, double shear_modulus_pa, double chamber_height_m,
                       double gap_m, double wall_critical_height_m) {
  WallSolution w;
  // Stages 2-3 by their series in s = sqrt(g/3) where it is short (wall_chain.hpp), else stage by stage. The batch
  // kernel takes the same branch per pressure (batch_kernel.hpp).
  const double two_over_b = 2.0 / wall_critical_height_m;
  double m = 0.0;
  if (wallStagesBySeries(gauge_pa, atmospheric_pa, shear_modulus_pa, chamber_height_m, gap_m, two_over_b,
                         w.stretch_excess, w.bulge_m, m)) {
    if (w.bulge_m > gap_m) w.half = halfAngleOfWall(w.bulge_m, gap_m, two_over_b, m);  // else apart: theta = 0
    return w;
  }
  w.stretch_excess = stretchExcess(energyGroup(gauge_pa, atmospheric_pa, shear_modulus_pa));
  w.bulge_m = bulge(w.stretch_excess, chamber_height_m);
  w.half = halfAngle(w.bulge_m, gap_m, wall_critical_height_m);
  return w;
}

FirstJointSeries firstJointSeries(double base_wall_share) {
  const double a = 1.0 + base_wall_share;
  double b[20];
  b[0] = 1.0;
  b[1] = a;
  for (int n = 1; n + 1 < 20; ++n) b[n + 1] = (a * b[n] + (n - 1) * b[n - 1]) / (n + 1);
  FirstJointSeries series{};
  for (int k = 0; k < 10; ++k) {
    series.cos_c[k] = (k % 2 == 0 ? 1.0 : -1.0) * b[2 * k];
    series.sin_c[k] = (k % 2 == 0 ? 1.0 : -1.0) * b[2 * k + 1];
  }
  return series;
}

double bulgeForHalfAngle(double half_angle_rad, double gap_m, double wall_critical_height_m) {
  const double b = wall_critical_height_m;
  const double k = gap_m / b;
  const double s = std::sin(half_angle_rad);
  return b / (2.0 * std::cos(half_angle_rad)) * (s + k + std::sqrt(2.0 * k * s + k * k));
}

namespace paper {

double stretch(double g) {
  // Eq 10-12, as printed (the 180 of eq 11 is pi: the paper's MATLAB took it as 180 radians, docs/MODEL.md).
  const double t = std::sqrt(-1.0 - std::pow(-(g + 3.0), 3) / 27.0);
  const double phi = kPi + std::atan(t / -1.0);
  return 2.0 * std::cbrt(std::sqrt(1.0 + t * t)) * std::cos(phi / 3.0);
}

double bulge(double stretch, double chamber_height_m) {
  return chamber_height_m / 2.0 * (std::sqrt(2.0 * stretch * stretch - 1.0) - 1.0);
}

std::array<double, 5> quarticCoefficients(double h, double c, double b) {
  const double a = (b * b - 4 * h * h) * (b * b - 4 * h * h) + 16 * b * b * h * h;       // eq 18
  const double bb = 32 * c * b * h * h;                                                  // eq 19
  const double cc = 16 * (c * h) * (c * h) - 16 * b * b * h * h + 8 * h * h * (b * b - 4 * h * h);  // eq 20
  const double dd = -32 * c * b * h * h;                                                 // eq 21
  const double ee = 16 * h * h * h * h - 16 * (c * h) * (c * h);                         // eq 22
  return {a, bb, cc, dd, ee};
}

FerrariTerms ferrariTerms(const std::array<double, 5>& quartic) {
  const double a = quartic[0], bq = quartic[1], cq = quartic[2], dq = quartic[3], eq = quartic[4];
  FerrariTerms t;
  // Eq 23-27: depress with y = x - B/(4A).
  t.p = bq * bq / (8 * a * a) + cq / a - bq * bq / (2 * a * a);
  t.q = bq * bq * bq / (8 * a * a * a) - cq * bq / (2 * a * a) + dq / a;
  t.r = std::pow(bq, 4) / (256 * std::pow(a, 4)) - std::pow(bq, 4) / (64 * std::pow(a, 4)) +
        cq * bq * bq / (16 * a * a * a) - dq * bq / (4 * a * a) + eq / a;
  // Eq 29-30: the resolvent cubic of eq 28, depressed with alpha = beta - p/3.
  const double p = t.p, q = t.q, r = t.r;
  t.p2 = (-8 * p * p / 9 - 16 * p * p / 9 + 16 * p * p / 3 - 2 * p * p + 8 * r) / -8;
  t.q2 = (2 * p * p * p / 3 - 8 * p * r / 3 + q * q - 8 * p * p * p / 9 + 8 * p * p * p / 27) / -8;
  t.discriminant = t.q2 * t.q2 / 4 + t.p2 * t.p2 * t.p2 / 27;
  return t;
}

double halfAngle(double h, double c, double b) {
  if (!(h > c)) return 0.0;
  const auto coef = quarticCoefficients(h, c, b);
  const double a = coef[0], bq = coef[1];
  const FerrariTerms t = ferrariTerms(coef);
  const double p = t.p, q = t.q, p2 = t.p2, q2 = t.q2, disc = t.discriminant;
  // Eq 31-33: Cardano, piecewise in the sign of the discriminant. Eq 33's first branch is printed with
  // -q2^2/4 under the first cube root; the Cardano form it names has -q2/2. Eq 32's arctangent takes the same
  // second-quadrant shift that the paper states for eq 11 (atan2).
  double beta;
  if (disc >= 0) {
    beta = std::cbrt(-q2 / 2 + std::sqrt(disc)) + std::cbrt(-q2 / 2 - std::sqrt(disc));
  } else {
    const double big_q2 = std::sqrt(-q2 * q2 / 4 - p2 * p2 * p2 / 27);  // eq 31
    const double phi2 = std::atan2(big_q2, -q2 / 2);                  // eq 32
    beta = 2 * std::cbrt(std::sqrt((q2 / 2) * (q2 / 2) + big_q2 * big_q2)) * std::cos(phi2 / 3);
  }
  const double alpha0 = beta - p / 3;
  const double x0 = q / (4 * alpha0);  // eq 34
  // Eq 35: the four roots; the sign in front of sqrt(2 alpha0) and the sign of x0 sqrt(2 alpha0) go together.
  const double s2a = std::sqrt(2 * alpha0);
  double best = std::numeric_limits<double>::quiet_NaN();
  double best_residual = 1e-6;  // relative residual in Wang's relation a root must beat to count
  for (int sign_outer : {+1, -1}) {
    const double inner = 2 * alpha0 - 4 * (sign_outer * x0 * s2a + p / 2 + alpha0);
    if (!(inner >= 0)) continue;  // complex pair
    for (int sign_inner : {+1, -1}) {
      const double x = (sign_outer * s2a + sign_inner * std::sqrt(inner)) / 2;
      const double y = x - bq / (4 * a);  // eq 23
      if (!(y >= 0 && y <= 1)) continue;
      const double theta = std::asin(y);
      const double residual = std::fabs(bulgeForHalfAngle(theta, c, b) - h) / h;
      if (residual < best_residual) {
        best_residual = residual;
        best = theta;
      }
    }
  }
  return best;
}

}  // namespace paper

}  // namespace pneumatic_finger
