// Arithmetic written once for a plain double and for a pack of doubles (GCC/Clang vector extensions), so that the
// single evaluation and the batch kernel (batch_kernel.hpp) round identically: the batch answers bit for bit what
// FingerModel::evaluate answers.
//
// Internal header of src/core (not installed). Everything here has internal linkage on purpose: the batch kernel is
// compiled once per instruction set (batch_generic.cpp, batch_avx2.cpp, batch_avx512.cpp), and an inline function
// with external linkage could be merged by the linker with a copy built for a wider instruction set than the machine
// has. Only +, -, *, / and sqrt are used, which IEEE 754 rounds the same way in every instruction set; the core is
// compiled with -ffp-contract=off so that no build fuses a multiply and an add in one place and not the other.
#pragma once

#include <cstddef>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#pragma GCC diagnostic push
// GCC 12's _mm512_sqrt_pd starts from _mm512_undefined_pd(), which -Wuninitialized reports by mistake.
#pragma GCC diagnostic ignored "-Wuninitialized"

namespace pneumatic_finger {
namespace {  // NOLINT(build/namespaces): see above, internal linkage per instruction set

typedef double Pack4 __attribute__((vector_size(32)));
typedef double Pack8 __attribute__((vector_size(64)));

template <class T>
constexpr int lanesOf() {
  return static_cast<int>(sizeof(T) / sizeof(double));
}

/// A pack with every lane @p x (a plain double stays a double).
template <class T>
inline T splat(double x) {
  if constexpr (lanesOf<T>() == 1) {
    return x;
  } else {
    return T{} + x;
  }
}

/// sqrt lane by lane (correctly rounded, as std::sqrt). A template, so that a translation unit instantiates only the
/// packs it uses.
template <class T>
inline T sqrtOf(T x) {
  if constexpr (lanesOf<T>() == 1) {
    return __builtin_sqrt(x);
#if defined(__AVX__)
  } else if constexpr (lanesOf<T>() == 4) {
    return reinterpret_cast<T>(_mm256_sqrt_pd(reinterpret_cast<__m256d>(x)));
#endif
#if defined(__AVX512F__)
  } else if constexpr (lanesOf<T>() == 8) {
    return reinterpret_cast<T>(_mm512_sqrt_pd(reinterpret_cast<__m512d>(x)));
#endif
  } else {
    T r;
    for (int i = 0; i < lanesOf<T>(); ++i) r[i] = __builtin_sqrt(x[i]);
    return r;
  }
}

/// True when any lane of a comparison result is set.
inline bool anyOf(bool m) { return m; }
template <class M>
inline bool anyOf(M m) {
  for (std::size_t i = 0; i < sizeof(M) / sizeof(m[0]); ++i) {
    if (m[i]) return true;
  }
  return false;
}

/// atan(t) for t >= 0 (and +inf; also right for t > -tan(pi/8)), to about one ulp (test: OwnArctangent): the
/// reduction of Cody and Waite's atan (t > tan 3pi/8: pi/2 + atan(-1/t); t > tan pi/8: pi/4 + atan((t - 1)/(t + 1)))
/// leaves |x| <= tan(pi/8), where atan(x) = x + x z P(z)/Q(z), z = x^2, with the [5/5] Pade approximant of
/// (atan(x) - x)/(x z) (relative error 2.7e-17 at the end of the range; scripts/atan_coefficients.py derives it).
/// P and Q go by Estrin's scheme (three levels of independent products instead of a chain of five). Written without
/// branches so that a pack takes it lane by lane; a plain double skips the reduction's division where it divides by
/// 1, which changes no bit (t/1 = t) and saves its latency in the single evaluation.
/// Why our own: glibc's atan has no pack form, and a pack must round as the single evaluation does.
template <class T>
inline T atanNonNegative(T t) {
  const auto big = t > splat<T>(2.4142135623730950488);
  const auto mid = t > splat<T>(0.4142135623730950488);
  const T one = splat<T>(1.0);
  // pi/2 and pi/4 as a double plus the part a double leaves out, added last to the small term.
  const T base_hi = big ? splat<T>(1.5707963267948966) : (mid ? splat<T>(0.7853981633974483) : splat<T>(0.0));
  const T base_lo = big ? splat<T>(6.123233995736766e-17) : (mid ? splat<T>(3.061616997868383e-17) : splat<T>(0.0));
  T x;
  if constexpr (lanesOf<T>() == 1) {
    x = big ? -1.0 / t : (mid ? (t - 1.0) / (t + 1.0) : t);
  } else {
    x = (big ? splat<T>(-1.0) : (mid ? t - one : t)) / (big ? t : (mid ? t + one : one));
  }
  const T z = x * x;
  const T z2 = z * z;
  const T z4 = z2 * z2;
  const T p = (splat<T>(-0.33333333333333333333) + z * splat<T>(-0.74202898550724637681)) +
              z2 * (splat<T>(-0.56452726017943409248) + z * splat<T>(-0.16795612218953180052)) +
              z4 * (splat<T>(-0.015611847679228407263) + z * splat<T>(-0.00004662874112713545054));
  const T q = (one + z * splat<T>(2.8260869565217391304)) +
              z2 * (splat<T>(2.9606625258799171843) + z * splat<T>(1.402419091206276561)) +
              z4 * (splat<T>(0.28873334230717458608) + z * splat<T>(0.019248889487144972405));
  return base_hi + (x + (x * z * (p / q) + base_lo));
}

/// cos(x) and sin(x) for 0 <= x <= pi/2 by their Taylor series to x^22 and x^23 (the first term left out is below
/// 2e-18 there), in Horner form in x^2; absolute error about one ulp. Shared by the single evaluation and the batch
/// kernel for joint 1's base half angle (docs/MODEL.md stage 5), so that both round it alike.
template <class T>
inline void sinCosSmall(T x, T& cos_x, T& sin_x) {
  const T z = x * x;
  // sin x / x = sum_k (-z)^k / (2k+1)!, cos x = sum_k (-z)^k / (2k)!, k = 0..11. With b_k = (-1)^k times the Horner
  // partial sum, b_k = 1/(2k+1)! - z b_{k+1}: every coefficient positive, b_0 the sum.
  T s = splat<T>(1.0 / 25852016738884976640000.0);  // 1/23!
  T c = splat<T>(1.0 / 1124000727777607680000.0);   // 1/22!
  const double sin_coefficients[11] = {1.0 / 51090942171709440000.0, 1.0 / 121645100408832000.0,
                                       1.0 / 355687428096000.0,      1.0 / 1307674368000.0,
                                       1.0 / 6227020800.0,           1.0 / 39916800.0,
                                       1.0 / 362880.0,               1.0 / 5040.0,
                                       1.0 / 120.0,                  1.0 / 6.0,
                                       1.0};
  const double cos_coefficients[11] = {1.0 / 2432902008176640000.0, 1.0 / 6402373705728000.0,
                                       1.0 / 20922789888000.0,      1.0 / 87178291200.0,
                                       1.0 / 479001600.0,           1.0 / 3628800.0,
                                       1.0 / 40320.0,               1.0 / 720.0,
                                       1.0 / 24.0,                  1.0 / 2.0,
                                       1.0};
  for (int k = 0; k < 11; ++k) {
    s = splat<T>(sin_coefficients[k]) - z * s;
    c = splat<T>(cos_coefficients[k]) - z * c;
  }
  sin_x = x * s;
  cos_x = c;
}

/// The directions of the N segments of a finger whose chambers are identical (docs/MODEL.md stage 6): segment 1
/// points along Theta_1 = theta_0 + theta, and each later one turns by r = e^(2 i theta) more: segment n along
/// Theta_1 + 2 (n - 1) theta. r^(2^k) come from squaring and every direction from one product with a power already
/// there, so the longest chain of dependent complex products is log2(N) + 1 long instead of N - 1 (a chain of
/// rotations is what limited the latency).
/// @param first_c, first_s cos and sin of Theta_1
/// @param cos_half, sin_half cos and sin of theta
/// @param[out] dir_c, dir_s cos and sin of Theta_1..Theta_N (N entries each)
template <class T>
inline void uniformDirections(T first_c, T first_s, T cos_half, T sin_half, int chamber_count, T* dir_c, T* dir_s) {
  // r = e^(2 i theta): cos 2 theta as a product, which does not cancel near pi/4.
  T pow_c = (cos_half - sin_half) * (cos_half + sin_half);
  T pow_s = splat<T>(2.0) * sin_half * cos_half;
  dir_c[0] = first_c;
  dir_s[0] = first_s;
  for (int done = 1; done < chamber_count; done *= 2) {
    // Directions done..2 done - 1 are directions 0..done - 1 turned by r^done.
    for (int j = done; j < 2 * done && j < chamber_count; ++j) {
      dir_c[j] = dir_c[j - done] * pow_c - dir_s[j - done] * pow_s;
      dir_s[j] = dir_s[j - done] * pow_c + dir_c[j - done] * pow_s;
    }
    const T c2 = (pow_c - pow_s) * (pow_c + pow_s);
    pow_s = splat<T>(2.0) * pow_s * pow_c;
    pow_c = c2;
  }
}

/// Joint 1 of identical chambers (docs/MODEL.md stage 5): q_1 = theta_0 + theta with theta_0 = s0 theta, and the
/// direction of segment 1, e^(i q_1) = e^(i theta_0) e^(i theta). With s0 = 0 (an inert base face) nothing is
/// computed: q_1 = theta and the direction is theta's own, exactly.
template <class T>
inline T firstJoint(double base_wall_share, T theta, T cos_half, T sin_half, T& first_c, T& first_s) {
  if (base_wall_share == 0.0) {
    first_c = cos_half;
    first_s = sin_half;
    return theta;
  }
  const T theta0 = base_wall_share * theta;
  T c0, s0;
  sinCosSmall(theta0, c0, s0);
  first_c = c0 * cos_half - s0 * sin_half;
  first_s = s0 * cos_half + c0 * sin_half;
  return theta0 + theta;
}

}  // namespace
}  // namespace pneumatic_finger

#pragma GCC diagnostic pop
