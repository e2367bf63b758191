#include "pneumatic_finger/stages.hpp"

#include <cmath>
#include <limits>

namespace pneumatic_finger {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kHalfPi = kPi / 2;
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
  const double g = (gauge_pa / atmospheric_pa) * ((2.0 * atmospheric_pa + gauge_pa) / shear_modulus_pa);
  return g < kMaxEnergyGroup ? g : kMaxEnergyGroup;
}

double stretchExcess(double g) {
  if (!(g > 0.0)) return 0.0;
  // Initial guess: a rational blend of the two asymptotes, delta ~ s + s^2/3 (small g, s = sqrt(g/3)) and
  // delta ~ sqrt(3) s (large g); within 4 % of the root for every g (checked in the tests).
  const double s = std::sqrt(g / 3.0);
  double delta = s * (3.0 + 2.3660254037844386 * s) / (3.0 + 1.3660254037844386 * s);
  // Newton on F(delta) = delta - R(delta), R = sqrt(g (1 + delta)/(3 + delta)). R' = R/((1 + delta)(3 + delta))
  // lies in [0, 0.134], so F' >= 0.866: the iteration is globally convergent and every term is positive.
  for (int i = 0; i < 32; ++i) {
    const double one_p = 1.0 + delta;
    const double three_p = 3.0 + delta;
    const double r = std::sqrt(g * (one_p / three_p));
    const double prod = one_p * three_p;
    const double step = (delta - r) * prod / (prod - r);
    delta -= step;
    if (std::fabs(step) <= 1e-10 * delta) break;  // quadratic: the next step would be below one ulp
  }
  return delta;
}

double bulge(double stretch_excess, double chamber_height_m) {
  const double d = stretch_excess;
  return chamber_height_m * d * (2.0 + d) / (std::sqrt(1.0 + d * (4.0 + 2.0 * d)) + 1.0);
}

HalfAngle halfAngle(double bulge_m, double gap_m, double wall_critical_height_m) {
  HalfAngle out;
  if (!(bulge_m > gap_m)) return out;  // walls not in contact (MODEL.md stage 4)
  const double b = wall_critical_height_m;
  const double big_h = 2.0 * bulge_m / b;
  if (!(big_h < 1e200)) {  // tan(theta) ~ H > 1e200: theta = pi/2 to the last bit
    out.rad = kHalfPi;
    out.cos = 0.0;
    out.sin = 1.0;
    return out;
  }
  // m = sqrt(2kH) = 2 sqrt(h c)/b; D = H - m, formed as H (H - 2k)/(H + m) so that it keeps its digits
  // where h -> c and both H and m tend to 2k.
  const double m = 2.0 * std::sqrt(bulge_m) * std::sqrt(gap_m) / b;
  const double d = big_h * (2.0 * (bulge_m - gap_m) / b) / (big_h + m);
  // f(t) = t + m (w(t) - 1) - D is increasing; its root lies in [D - m (w(D) - 1), D].
  double lo = 0.0;
  double hi = d;
  double t = d - m * quarterPower(d).w_m1;
  if (t > lo) lo = t; else t = 0.5 * hi;
  int iterations = 0;
  for (; iterations < 64; ++iterations) {
    const QuarterPower q = quarterPower(t);
    const double f = t + m * q.w_m1 - d;
    if (f == 0.0) break;
    if (f > 0.0) hi = t; else lo = t;
    const double fprime = 1.0 + 0.5 * m * t / (q.w * q.w * q.w);
    double next = t - f / fprime;
    bool newton = true;
    if (!(next >= lo && next <= hi)) {  // safeguard: stay inside the bracket
      next = 0.5 * (lo + hi);
      newton = false;
    }
    const double step = next - t;
    t = next;
    if (newton && std::fabs(step) <= 1e-10 * t) break;  // quadratic convergence: next step < 1 ulp
    if (hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * hi) break;
  }
  out.iterations = iterations + 1;
  out.rad = std::atan(t);
  if (t > kLargeTan) {
    out.cos = 1.0 / t;
    out.sin = 1.0;
  } else {
    out.cos = 1.0 / std::sqrt(1.0 + t * t);
    out.sin = t * out.cos;
  }
  return out;
}

double bulgeForHalfAngle(double half_angle_rad, double gap_m, double wall_critical_height_m) {
  const double b = wall_critical_height_m;
  const double k = gap_m / b;
  const double s = std::sin(half_angle_rad);
  return b / (2.0 * std::cos(half_angle_rad)) * (s + k + std::sqrt(2.0 * k * s + k * k));
}

namespace paper {

double stretch(double g) {
  // Eq 10-12, as printed (the 180 of eq 11 is pi: the paper's MATLAB took it as 180 radians, MODEL.md).
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
