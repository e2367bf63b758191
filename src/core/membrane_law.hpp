// The thin membrane's law, P and dP/ddelta at a stretch excess, written once for a plain double and for a pack of
// doubles (simd_math.hpp), as wall_chain.hpp is for the paper's chain: membrane_wall.cpp's Newton steps and the batch's
// membrane packs (membrane_kernel.hpp) instantiate the same template, so that the batch rounds as the single evaluation
// does. Internal header of src/core; internal linkage on purpose (simd_math.hpp says why).
#pragma once

#include "simd_math.hpp"

namespace pneumatic_finger {
namespace {  // NOLINT(build/namespaces): internal linkage per instruction set (simd_math.hpp)

/// lambda^6 - 1 as a polynomial in delta (no cancellation near rest).
template <class T>
inline T sixthPowerMinusOne(T d) {
  return d * (6.0 + d * (15.0 + d * (20.0 + d * (15.0 + d * (6.0 + d)))));
}

/// I1 - 3 = (lambda^2 - 1)^2 (2 lambda^2 + 1) / lambda^4 for the equibiaxial membrane, from delta.
template <class T>
inline T firstInvariantExcess(T d) {
  const T lam = 1.0 + d, lam_sq = lam * lam, sq_m1 = d * (2.0 + d);
  return sq_m1 * sq_m1 * (2.0 * lam_sq + 1.0) / (lam_sq * lam_sq);
}

/// The thin membrane's P and dP/ddelta at @p d together (they share lambda^6 - 1 and the Gent factor), for the
/// pressure scale 4 mu t / L and J_m (0: Neo-Hookean): d/dlambda (1/lambda - 1/lambda^7) = (7 - lambda^6)/lambda^8,
/// and d ln(J_m/(J_m - e)) = e'/(J_m - e), with e' = 4 (lambda^6 - 1)/lambda^5. P = +inf (and the slope) at or beyond
/// the lock.
template <class T>
inline void thinGaugeAndSlopeOf(double pressure_scale_pa, double locking_jm, T d, T& gauge_pa, T& slope_pa) {
  // One reciprocal, 1/lambda^8, serves the three powers the law divides by (lambda^7, lambda^8, lambda^5): a Newton
  // step waits on this function, and a division's latency is several products'.
  const T lam = 1.0 + d, u = sixthPowerMinusOne(d), lam2 = lam * lam, lam4 = lam2 * lam2;
  const T inv_lam8 = 1.0 / (lam4 * lam4);
  gauge_pa = pressure_scale_pa * (u * lam * inv_lam8);
  slope_pa = pressure_scale_pa * ((6.0 - u) * inv_lam8);
  if (locking_jm == 0.0) return;
  const T room = locking_jm - firstInvariantExcess(d);
  const T inv_room = 1.0 / room;
  const T gent = locking_jm * inv_room;
  const T slope = (slope_pa + gauge_pa * ((4.0 * u) * (lam2 * lam * inv_lam8)) * inv_room) * gent;
  const T gauge = gauge_pa * gent;
  const auto open = room > splat<T>(0.0);  // else at or beyond the lock
  const T inf = splat<T>(__builtin_inf());
  gauge_pa = open ? gauge : inf;
  slope_pa = open ? slope : inf;
}

}  // namespace
}  // namespace pneumatic_finger
