// The thick wall's law (docs/MODEL.md, "The thick wall").
#include "thick_wall.hpp"

#include <cmath>
#include <limits>

namespace pneumatic_finger {

namespace {

// (lambda^-2 + lambda^-5) G(lambda): the integrand over 2 mu. G = J_m/(J_m - (2 lambda^2 + lambda^-4 - 3)).
double integrand(const MembraneWall& w, double lam) {
  const double l2 = lam * lam, l4 = l2 * l2;
  const double f = (1.0 + 1.0 / (l2 * lam)) / l2;
  if (w.locking_jm == 0.0) return f;
  const double room = w.locking_jm - (2.0 * l2 + 1.0 / l4 - 3.0);
  return room > 0.0 ? f * w.locking_jm / room : std::numeric_limits<double>::infinity();
}

// The Gent integrand's integral over [lambda_b, lambda_a], lambda_a - lambda_b = gap given apart (near rest it is a difference of two numbers
// near 1, whose digits the subtraction would lose). In x = lambda^2 the integrand is -(J_m/2)(lambda^2 + 1/lambda) /
// prod(x - x_i), and partial fractions give each root's share in closed form (docs/MODEL.md, "The thick wall"): the
// lambda^2 part a log or an arctangent per root, the 1/lambda part logs of x - x_i, taken against log x (their
// weights sum to zero), whose ratios stay small for a large J_m where the logs themselves would cancel.
double gentIntegral(const MembraneWall& w, double delta, double delta_b, double gap) {
  const double xs = w.gent_root_x[0], xn = w.gent_root_x[1], xl = w.gent_root_x[2];
  const double s = w.gent_root_sqrt[0], b = w.gent_root_sqrt[1], big_s = w.gent_root_sqrt[2];
  const double la = 1.0 + delta, lb = 1.0 + delta_b, xa = la * la, xb = lb * lb, dx = gap * (la + lb);
  const double to_lock = w.locking_stretch_excess - delta_b;  // big_s - lb without the 1 - 1
  // int dlambda/(lambda^2 - x_i), each as the log of one ratio (or one arctangent) of its ends.
  const double i_s = std::log1p(2.0 * s * gap / ((lb - s) * (la + s))) / (2.0 * s);
  const double i_n = std::atan(gap * b / (b * b + la * lb)) / b;
  const double i_l = std::log1p(-2.0 * big_s * gap / (to_lock * (big_s + la))) / (2.0 * big_s);
  const double* a = w.gent_weight.data();
  const double lambda_squared_part = a[0] * xs * i_s + a[1] * xn * i_n + a[2] * xl * i_l;
  double inverse_lambda_part = 0.0;  // (1/2) sum (a_i/x_i) [log(x - x_i) - log x] between the ends
  for (std::size_t i = 0; i < 3; ++i) {
    const double xi = w.gent_root_x[i];
    inverse_lambda_part += a[i] / xi * std::log1p(xi * dx / ((xb - xi) * xa));
  }
  return -0.5 * w.locking_jm * (lambda_squared_part + 0.5 * inverse_lambda_part);
}

}  // namespace

void setThickGentRoots(MembraneWall& w) {
  const double jm = w.locking_jm, xl = (1.0 + w.locking_stretch_excess) * (1.0 + w.locking_stretch_excess);
  // The cubic is 2 (x - x_l)(x^2 + p x + q); its own identity at x_l gives p and q without cancellation.
  const double p = -0.5 / (xl * xl), q = -0.5 / xl;
  double xs = 0.5 * (-p + std::sqrt(p * p - 4.0 * q)), xn = q / xs;
  const auto cubic = [jm](double x) { return (2.0 * x - (jm + 3.0)) * x * x + 1.0; };
  const auto slope = [jm](double x) { return (6.0 * x - 2.0 * (jm + 3.0)) * x; };
  for (int step = 0; step < 2; ++step) {  // polish both on the cubic itself
    xs -= cubic(xs) / slope(xs);
    xn -= cubic(xn) / slope(xn);
  }
  w.gent_root_x = {xs, xn, xl};
  w.gent_root_sqrt = {std::sqrt(xs), std::sqrt(-xn), 1.0 + w.locking_stretch_excess};
  for (std::size_t i = 0; i < 3; ++i) {
    const double xi = w.gent_root_x[i];
    w.gent_weight[i] = 1.0 / ((xi - w.gent_root_x[(i + 1) % 3]) * (xi - w.gent_root_x[(i + 2) % 3]));
  }
}

double thickOuterStretchExcess(const MembraneWall& w, double delta) {
  const double u = delta * (3.0 + delta * (3.0 + delta));  // lambda_a^3 - 1
  return std::expm1(std::log1p(w.inner_outer_volume_ratio * u) / 3.0);
}

namespace {

// P at inner stretch excess @p delta whose outer face's is @p delta_b.
double gaugeForStretches(const MembraneWall& w, double delta, double delta_b) {
  if (w.locking_jm != 0.0 && !(delta < w.locking_stretch_excess)) return std::numeric_limits<double>::infinity();
  const double la = 1.0 + delta, lb = 1.0 + delta_b, gap = delta - delta_b;  // lambda_a - lambda_b, without 1 - 1
  const double mu = w.pressure_scale_pa;
  if (w.locking_jm == 0.0) {
    // 2 mu [1/lambda_b - 1/lambda_a + (lambda_b^-4 - lambda_a^-4)/4], the difference factored out.
    const double la2 = la * la, lb2 = lb * lb;
    return mu * gap * (2.0 / (la * lb) + (la + lb) * (la2 + lb2) / (2.0 * la2 * la2 * lb2 * lb2));
  }
  return 2.0 * mu * gentIntegral(w, delta, delta_b, gap);
}

// dP/ddelta at @p delta whose outer face's stretch excess is @p delta_b.
double slopeForStretches(const MembraneWall& w, double delta, double delta_b) {
  const double la = 1.0 + delta, lb = 1.0 + delta_b;
  const double db_da = w.inner_outer_volume_ratio * la * la / (lb * lb);
  return 2.0 * w.pressure_scale_pa * (integrand(w, la) - integrand(w, lb) * db_da);
}

}  // namespace

double thickGaugeForStretchExcess(const MembraneWall& w, double delta) {
  return gaugeForStretches(w, delta, thickOuterStretchExcess(w, delta));
}

double thickGaugeSlope(const MembraneWall& w, double delta) {
  return slopeForStretches(w, delta, thickOuterStretchExcess(w, delta));
}

void thickGaugeAndSlope(const MembraneWall& w, double delta, double& gauge_pa, double& slope_pa) {
  const double delta_b = thickOuterStretchExcess(w, delta);  // once for both
  gauge_pa = gaugeForStretches(w, delta, delta_b);
  slope_pa = slopeForStretches(w, delta, delta_b);
}

}  // namespace pneumatic_finger
