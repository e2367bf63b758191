// The rising branch's inverse (docs/MODEL.md, "The wall's inverse"): the stretch excess for a pressure, delta(P), as
// piecewise polynomials built and checked against the law when the wall is built (wall_inverse.cpp), so that an
// evaluation costs a square root and one polynomial instead of Newton steps on the law (whose thick form costs five
// logarithms, an arctangent and a cube root a step).
//
// With q = P / P_top and s = sqrt(1 - q), delta = q g(s): s turns the limit point's square-root fold (delta - delta_lim
// ~ -sqrt(P_lim - P)) into a smooth function, and the factor q keeps delta's relative precision near rest, where delta
// is proportional to P. g is a degree-15 polynomial in x in [-1, 1] on each of MembraneWall::inverse_pieces equal
// pieces of s in [0, 1]. Written once for a plain double and a pack (simd_math.hpp), as membrane_law.hpp is, so that
// the batch's packs round as the single evaluation does. Internal header of src/core; internal linkage on purpose.
#pragma once

#include <cstddef>

#include "pneumatic_finger/core/membrane_wall.hpp"
#include "simd_math.hpp"

namespace pneumatic_finger {

/// membraneStretchExcess by Newton steps from the starting table alone (membrane_wall.cpp): what the inverse is
/// built and checked against, and what answers where it has no piece.
double membraneNewtonStretchExcess(const MembraneWall& wall, double gauge_pa);

namespace {  // NOLINT(build/namespaces): internal linkage per instruction set (simd_math.hpp)

/// g on one piece at x: Estrin's scheme (pairs, then x^2, x^4 and x^8 combine them: four levels of independent
/// products where Horner's rule would chain fifteen).
template <class T>
inline T inversePolynomial(const T (&c)[MembraneWall::kInverseCoefficients], T x) {
  static_assert(MembraneWall::kInverseCoefficients == 16, "the inverse's Estrin scheme is written for degree 15");
  const T x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
  T pair[8];
  for (int i = 0; i < 8; ++i) pair[i] = c[2 * i] + c[2 * i + 1] * x;
  const T q0 = pair[0] + pair[1] * x2, q1 = pair[2] + pair[3] * x2, q2 = pair[4] + pair[5] * x2, q3 = pair[6] + pair[7] * x2;
  return (q0 + q1 * x4) + (q2 + q3 * x4) * x8;
}

/// s K for pressures @p p: where they fall among the pieces.
template <class T>
inline T inversePosition(const MembraneWall& w, T p) {
  return sqrtOf((w.inverse_top_gauge_pa - p) * w.inverse_scale_per_pa) * static_cast<double>(w.inverse_pieces);
}

/// Whether @p w's inverse answers @p p (> 0: rest is answered exactly elsewhere; below the limit point and up to the
/// inverse's top).
inline bool inverseCovers(const MembraneWall& w, double p) {
  return w.inverse_pieces > 0 && p > 0.0 && p <= w.inverse_top_gauge_pa && p < w.limit_gauge_pa;
}

/// The piece at @p position (s K; s = 0, the top, falls in the first piece, and s = 1, rest, in the last) and its
/// row of coefficients (delta's, then the outer face's where the wall has them); @p x the position within it.
inline const double* inversePiece(const MembraneWall& w, double position, double& x) {
  int piece = static_cast<int>(position);
  piece = piece < w.inverse_pieces ? piece : w.inverse_pieces - 1;
  x = 2.0 * (position - piece) - 1.0;
  const auto stride = static_cast<std::size_t>(w.inverse_functions) * MembraneWall::kInverseCoefficients;
  return &w.inverse_coefficients[static_cast<std::size_t>(piece) * stride];
}

/// delta for a pressure @p p in [0, inverse_top_gauge_pa] (the caller's to check; inverse_pieces > 0), and, when
/// @p outer_stretch_excess is given (a wall whose outer face bends, inverse_functions 2), the outer face's delta_b.
inline double risingInverse(const MembraneWall& w, double p, double* outer_stretch_excess = nullptr) {
  constexpr int kTerms = MembraneWall::kInverseCoefficients;
  double x = 0.0, c[kTerms];
  const double* row = inversePiece(w, inversePosition(w, p), x);
  const double q = p * w.inverse_scale_per_pa;
  for (int j = 0; j < kTerms; ++j) c[j] = row[j];
  const double delta = q * inversePolynomial(c, x);
  if (outer_stretch_excess != nullptr) {
    for (int j = 0; j < kTerms; ++j) c[j] = row[kTerms + j];
    *outer_stretch_excess = q * inversePolynomial(c, x);
  }
  return delta;
}

/// risingInverse lane by lane for a pack, with the same operations.
template <class T>
inline T risingInversePack(const MembraneWall& w, T p, T* outer_stretch_excess = nullptr) {
  constexpr int kTerms = MembraneWall::kInverseCoefficients;
  const T position = inversePosition(w, p);
  T x = splat<T>(0.0), c[kTerms] = {}, outer[kTerms] = {};
  for (int i = 0; i < lanesOf<T>(); ++i) {
    double xi = 0.0;
    const double* row = inversePiece(w, position[i], xi);
    x[i] = xi;
    for (int j = 0; j < kTerms; ++j) c[j][i] = row[j];
    if (outer_stretch_excess != nullptr) {
      for (int j = 0; j < kTerms; ++j) outer[j][i] = row[kTerms + j];
    }
  }
  const T q = p * w.inverse_scale_per_pa;
  if (outer_stretch_excess != nullptr) *outer_stretch_excess = q * inversePolynomial(outer, x);
  return q * inversePolynomial(c, x);
}

}  // namespace
}  // namespace pneumatic_finger
