// The thick wall's law (docs/MODEL.md, "The thick wall").
#include "thick_wall.hpp"

#include <array>
#include <cmath>
#include <limits>

namespace pneumatic_finger {

namespace {

constexpr int kNodes = 20;

// Gauss-Legendre nodes and weights on [-1, 1], by Newton's method on P_20 from Chebyshev's guesses (once).
struct GaussLegendre {
  std::array<double, kNodes> x, w;
  GaussLegendre() {
    const double pi = std::acos(-1.0);
    for (int i = 0; i < kNodes; ++i) {
      double z = std::cos(pi * (i + 0.75) / (kNodes + 0.5)), dp = 1.0;
      for (int step = 0; step < 100; ++step) {
        double p0 = 1.0, p1 = z;
        for (int k = 2; k <= kNodes; ++k) {
          const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
          p0 = p1, p1 = p2;
        }
        dp = kNodes * (z * p1 - p0) / (z * z - 1.0);
        const double dz = p1 / dp;
        z -= dz;
        if (std::fabs(dz) < 1e-17) break;
      }
      x[static_cast<std::size_t>(i)] = z;
      w[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
  }
};

const GaussLegendre& gaussLegendre() {
  static const GaussLegendre rule;
  return rule;
}

// (lambda^-2 + lambda^-5) G(lambda): the integrand over 2 mu. G = J_m/(J_m - (2 lambda^2 + lambda^-4 - 3)).
double integrand(const MembraneWall& w, double lam) {
  const double l2 = lam * lam, l4 = l2 * l2;
  const double f = (1.0 + 1.0 / (l2 * lam)) / l2;
  if (w.locking_jm == 0.0) return f;
  const double room = w.locking_jm - (2.0 * l2 + 1.0 / l4 - 3.0);
  return room > 0.0 ? f * w.locking_jm / room : std::numeric_limits<double>::infinity();
}

// The integrand over [lo, lo + width], width given apart (lambda_a - lambda_b near rest is a difference of two
// numbers near 1, whose digits the subtraction would lose): panels of Gauss-Legendre, each no wider than half its
// distance to the lock (the Gent factor's pole), so that every panel's rule converges fast.
double integral(const MembraneWall& w, double lo, double width) {
  const GaussLegendre& rule = gaussLegendre();
  const double to_lock = w.locking_stretch_excess + 1.0 - lo;  // +inf for Neo-Hookean
  double sum = 0.0;
  for (double a = 0.0; a < width;) {  // offsets from lo
    const double b = std::isfinite(to_lock) ? std::fmin(width, a + 0.5 * (to_lock - a)) : width;
    if (!(b > a)) break;
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    double panel = 0.0;
    for (int i = 0; i < kNodes; ++i) {
      const auto k = static_cast<std::size_t>(i);
      panel += rule.w[k] * integrand(w, lo + (mid + half * rule.x[k]));
    }
    sum += half * panel;
    a = b;
  }
  return sum;
}

}  // namespace

double thickOuterStretchExcess(const MembraneWall& w, double delta) {
  const double u = delta * (3.0 + delta * (3.0 + delta));  // lambda_a^3 - 1
  return std::expm1(std::log1p(w.inner_outer_volume_ratio * u) / 3.0);
}

double thickGaugeForStretchExcess(const MembraneWall& w, double delta) {
  if (w.locking_jm != 0.0 && !(delta < w.locking_stretch_excess)) return std::numeric_limits<double>::infinity();
  const double delta_b = thickOuterStretchExcess(w, delta);
  const double la = 1.0 + delta, lb = 1.0 + delta_b, gap = delta - delta_b;  // lambda_a - lambda_b, without 1 - 1
  const double mu = w.pressure_scale_pa;
  if (w.locking_jm == 0.0) {
    // 2 mu [1/lambda_b - 1/lambda_a + (lambda_b^-4 - lambda_a^-4)/4], the difference factored out.
    const double la2 = la * la, lb2 = lb * lb;
    return mu * gap * (2.0 / (la * lb) + (la + lb) * (la2 + lb2) / (2.0 * la2 * la2 * lb2 * lb2));
  }
  return 2.0 * mu * integral(w, lb, gap);
}

double thickGaugeSlope(const MembraneWall& w, double delta) {
  const double delta_b = thickOuterStretchExcess(w, delta);
  const double la = 1.0 + delta, lb = 1.0 + delta_b;
  const double db_da = w.inner_outer_volume_ratio * la * la / (lb * lb);
  return 2.0 * w.pressure_scale_pa * (integrand(w, la) - integrand(w, lb) * db_da);
}

}  // namespace pneumatic_finger
