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

/// The directions of the N segments of a finger whose chambers are identical (docs/MODEL.md stage 6): segment n
/// (n = 1..N) points along Theta_n = (2n - 1) theta, i.e. e^(i theta) r^(n-1) with r = e^(2 i theta). r^(2^k) come
/// from squaring and every direction from one product with a power already there, so the longest chain of dependent
/// complex products is log2(N) + 1 long instead of N - 1 (a chain of rotations is what limited the latency).
/// @param[out] dir_c, dir_s cos and sin of Theta_1..Theta_N (N entries each)
template <class T>
inline void uniformDirections(T cos_half, T sin_half, int chamber_count, T* dir_c, T* dir_s) {
  // r = e^(2 i theta): cos 2 theta as a product, which does not cancel near pi/4.
  T pow_c = (cos_half - sin_half) * (cos_half + sin_half);
  T pow_s = splat<T>(2.0) * sin_half * cos_half;
  dir_c[0] = cos_half;
  dir_s[0] = sin_half;
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

}  // namespace
}  // namespace pneumatic_finger

#pragma GCC diagnostic pop
