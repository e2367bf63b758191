#include "reference_quad.hpp"

#include <array>
#include <map>

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

namespace {

// 1/lambda - 1/lambda^7 = (lambda^6 - 1)/lambda^7, with lambda^6 - 1 = expm1(6 log1p(delta)): exact in quad down to the
// smallest delta (the literal difference would keep no digit below delta ~ 1e-34).
quad membraneP(const Membrane& w, quad lambda, quad delta) {
  const quad neo = 4 * quad(w.shear_modulus_pa) * w.wall_thickness_m / w.chamber_height_m *
                   (expm1q(6 * log1pq(delta)) / powq(lambda, 7));
  if (w.locking_jm == 0) return neo;
  const quad room = quad(w.locking_jm) - (2 * lambda * lambda + 1 / powq(lambda, 4) - 3);
  return room > 0 ? neo * w.locking_jm / room : quad(1e300) * quad(1e300);
}

// The sign of dP/dlambda: f'g - f g' for P ~ f/g, f = 1/lambda - 1/lambda^7, g = J_m - (I1 - 3) (g = 1 for J_m = 0).
quad membraneSlopeSign(const Membrane& w, quad lambda) {
  const quad f = 1 / lambda - 1 / powq(lambda, 7), fp = -1 / (lambda * lambda) + 7 / powq(lambda, 8);
  if (w.locking_jm == 0) return fp;
  const quad g = quad(w.locking_jm) - (2 * lambda * lambda + 1 / powq(lambda, 4) - 3);
  const quad gp = -(4 * lambda - 4 / powq(lambda, 5));
  return fp * g - f * gp;
}

quad membraneLimitLambdaUncached(const Membrane& w) {
  quad lock = 1e30;
  if (w.locking_jm > 0) {
    lock = bisect([&w](quad l) { return (2 * l * l + 1 / powq(l, 4) - 3) - w.locking_jm; }, quad(1), quad(1e6));
  }
  // Scan in lambda from just above rest to the lock (or far out), then bisect the first sign change.
  const quad top = w.locking_jm > 0 ? lock : quad(10);
  const int steps = 20000;
  quad previous = 1 + (top - 1) / steps;
  for (int i = 2; i < steps; ++i) {
    const quad l = 1 + (top - 1) * i / steps;
    if (membraneSlopeSign(w, l) <= 0) {
      return bisect([&w](quad x) { return -membraneSlopeSign(w, x); }, previous, l);
    }
    previous = l;
  }
  return quad(1e300) * quad(1e300);
}

// The scan is slow in quad; a test asks for the same wall many times.
quad membraneLimitLambda(const Membrane& w) {
  static std::map<std::array<double, 4>, quad> cache;
  const std::array<double, 4> key{w.shear_modulus_pa, w.wall_thickness_m, w.chamber_height_m, w.locking_jm};
  const auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  return cache[key] = membraneLimitLambdaUncached(w);
}

}  // namespace

double membraneLimitStretchExcess(const Membrane& wall) { return static_cast<double>(membraneLimitLambda(wall) - 1); }

double membraneLimitGaugePa(const Membrane& wall) {
  const quad l = membraneLimitLambda(wall);
  return l < quad(1e30) ? static_cast<double>(membraneP(wall, l, l - 1)) : static_cast<double>(l);
}

double membraneStretchExcess(const Membrane& wall, double gauge_pa) {
  if (!(gauge_pa > 0)) return 0;
  const quad top = membraneLimitLambda(wall);
  const quad hi = top < quad(1e30) ? top : quad(1e6);
  // P in delta = lambda - 1 (so that delta keeps its digits near rest): rising on [0, limit].
  return static_cast<double>(
      bisect([&](quad d) { return membraneP(wall, 1 + d, d) - quad(gauge_pa); }, quad(0), hi - 1));
}

double membraneGaugePa(const Membrane& wall, double stretch_excess) {
  return static_cast<double>(membraneP(wall, 1 + quad(stretch_excess), quad(stretch_excess)));
}

}  // namespace reference
