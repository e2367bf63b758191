#include "reference_quad.hpp"

extern "C" {
#include <quadmath.h>
}

namespace reference {

namespace {

using quad = __float128;

// Bisection on an increasing function f with f(lo) < 0 <= f(hi), until the midpoint is one of the ends.
template <typename F>
quad bisect(F f, quad lo, quad hi) {
  for (int i = 0; i < 20000; ++i) {
    const quad mid = lo + (hi - lo) / 2;
    if (mid <= lo || mid >= hi) break;
    (f(mid) < 0 ? lo : hi) = mid;
  }
  return (lo + hi) / 2;
}

quad energyGroupQ(quad p, quad p_o, quad mu) {
  if (!(p > 0)) return 0;
  return p * (2 * p_o + p) / (p_o * mu);  // docs/MODEL.md stage 1
}

// Stage 2: the largest root lambda of lambda^3 - (g + 3) lambda + 2, found as delta = lambda - 1 from docs/MODEL.md's
// equivalent delta^2 (3 + delta) - g (1 + delta) = 0. (Bisecting the cubic in lambda itself would lose half the
// digits near rest, where lambda = 1 is a double root: the derivative there is only ~6 delta.) The polynomial is
// -g at 0 and convex for delta >= 0, so it is negative up to the root and positive after: bisection on [0, hi].
quad stretchExcessQ(quad g) {
  if (g == 0) return 0;
  const quad hi = sqrtq(g) + 1;
  return bisect([g](quad d) { return d * d * (3 + d) - g * (1 + d); }, quad(0), hi);
}

// Stage 3 literally: (L/2)(sqrt(2 lambda^2 - 1) - 1). The quad precision absorbs the cancellation.
quad bulgeQ(quad delta, quad l) {
  const quad lambda = 1 + delta;
  return l / 2 * (sqrtq(2 * lambda * lambda - 1) - 1);
}

// Stage 4: eq 15, h(theta), increasing on [0, pi/2).
quad wangQ(quad theta, quad c, quad b) {
  const quad s = sinq(theta);
  return b / (2 * cosq(theta)) * (s + c / b + sqrtq(2 * c / b * s + c * c / (b * b)));
}

quad halfAngleQ(quad h, quad c, quad b) {
  if (!(h > c)) return 0;
  return bisect([&](quad t) { return wangQ(t, c, b) - h; }, quad(0), acosq(quad(0)));
}

}  // namespace

ChamberChain chamberChain(double gauge_pa, double atmospheric_pa, const ChamberGeometry& chamber) {
  const quad g = energyGroupQ(gauge_pa, atmospheric_pa, chamber.shear_modulus_pa);
  const quad delta = stretchExcessQ(g);
  const quad h = bulgeQ(delta, chamber.chamber_height_m);
  const quad theta = halfAngleQ(h, chamber.chamber_gap_m, chamber.wall_critical_height_m);
  return {static_cast<double>(g), static_cast<double>(delta), static_cast<double>(h),
          static_cast<double>(theta)};
}

double halfAngleForBulge(double bulge_m, double gap_m, double wall_critical_height_m) {
  return static_cast<double>(halfAngleQ(bulge_m, gap_m, wall_critical_height_m));
}

Finger finger(double gauge_pa, double atmospheric_pa, const std::vector<ChamberGeometry>& chambers,
              const std::vector<double>& segment_length_m, double base_segment_length_m, double base_wall_share) {
  const std::size_t n = chambers.size();
  std::vector<quad> theta(n);
  for (std::size_t i = 0; i < n; ++i) {
    const quad g = energyGroupQ(gauge_pa, atmospheric_pa, chambers[i].shear_modulus_pa);
    const quad h = bulgeQ(stretchExcessQ(g), chambers[i].chamber_height_m);
    theta[i] = halfAngleQ(h, chambers[i].chamber_gap_m, chambers[i].wall_critical_height_m);
  }
  Finger out;
  // Stage 5-6, eq 37-38: Theta_n = Theta_{n-1} + theta_{n-1} + theta_n; O_n = O_{n-1} + Z_{n-1}(cos, sin)(Theta_{n-1}).
  // theta_0, the base face's half angle, is s0 theta_1 (docs/MODEL.md stage 5).
  quad big_theta = 0, x = base_segment_length_m, y = 0;
  quad prev = n > 0 ? static_cast<quad>(base_wall_share) * theta[0] : 0;
  out.x_m = {0.0, static_cast<double>(x)};
  out.y_m = {0.0, 0.0};
  for (std::size_t i = 0; i < n; ++i) {
    const quad q = prev + theta[i];
    big_theta += q;
    x += segment_length_m[i] * cosq(big_theta);
    y += segment_length_m[i] * sinq(big_theta);
    out.half_angle_rad.push_back(static_cast<double>(theta[i]));
    out.joint_angle_rad.push_back(static_cast<double>(q));
    out.x_m.push_back(static_cast<double>(x));
    out.y_m.push_back(static_cast<double>(y));
    prev = theta[i];
  }
  out.tip_angle_rad = static_cast<double>(big_theta);
  return out;
}

}  // namespace reference
