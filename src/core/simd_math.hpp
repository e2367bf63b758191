// The math primitives, written once for a plain double and for a pack of doubles (GCC/Clang vector extensions): packs,
// square root, masks, the arctangent, Estrin's scheme, sine and cosine. The physics built on them, also written once
// for both, is in wall_chain.hpp (stages 1-4) and joint_chain.hpp (stages 5-6); the single evaluation and the batch
// kernel (batch_kernel.hpp) both instantiate it, so the batch answers bit for bit what FingerModel::evaluate answers.
//
// Internal header of src/core (not installed). Everything here has internal linkage on purpose: the batch kernel is
// compiled once per instruction set (batch_generic.cpp, batch_avx2.cpp, batch_avx512.cpp), and an inline function
// with external linkage could be merged by the linker with a copy built for a wider instruction set than the machine
// has. Only +, -, *, / and sqrt are used, which IEEE 754 rounds the same way in every instruction set; the core is
// compiled with -ffp-contract=off so that no build fuses a multiply and an add in one place and not the other.
#pragma once

#include <cstddef>

#include "pneumatic_finger/core/units.hpp"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#pragma GCC diagnostic push
// GCC 12's _mm512_sqrt_pd starts from _mm512_undefined_pd(), which -Wuninitialized reports by mistake.
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

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

/// The lanes a mask leaves out: !m for a plain double's bool, ~m for a pack's lane masks.
inline bool notOf(bool m) { return !m; }
template <class M>
inline M notOf(M m) {
  return ~m;
}

/// atan(t) for 0 <= t <= 1/8 by its Taylor series t + t z sum_{k=1..8} (-z)^(k-1)/(2k+1), z = t^2: the first term left
/// out, t^19/19, is below 3e-18 t there. No division, and Estrin's scheme (the pairs, then z^2 and z^4), so its
/// latency is about half the general form's.
constexpr double kAtanSmallLimit = 0.125;
template <class T>
inline T atanSmall(T t) {
  const T z = t * t;
  const T z2 = z * z;
  const T z4 = z2 * z2;
  const T p = (splat<T>(-1.0 / 3.0) + z * splat<T>(1.0 / 5.0)) + z2 * (splat<T>(-1.0 / 7.0) + z * splat<T>(1.0 / 9.0)) +
              z4 * ((splat<T>(-1.0 / 11.0) + z * splat<T>(1.0 / 13.0)) +
                    z2 * (splat<T>(-1.0 / 15.0) + z * splat<T>(1.0 / 17.0)));
  return t + t * z * p;
}

template <class T>
inline T atanGeneral(T t) {
  const auto big = t > splat<T>(2.4142135623730950488);
  const auto mid = t > splat<T>(0.4142135623730950488);
  const T one = splat<T>(1.0);
  // pi/2 and pi/4 as a double plus the part a double leaves out, added last to the small term.
  const T base_hi = big ? splat<T>(kHalfPi) : (mid ? splat<T>(kPi / 4) : splat<T>(0.0));
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

/// atan(t) for t >= 0 and +inf (not for t < 0, which the short form would take), to about one ulp (test:
/// OwnArctangent). Small arguments (t <= 1/8, which covers the walls' half angles up to 7 degrees, the validated range
/// of the calibrated finger) take atanSmall: no reduction and no division. Larger ones take the general form: the
/// reduction of Cody and Waite's atan (t > tan 3pi/8: pi/2 + atan(-1/t); t > tan pi/8: pi/4 + atan((t - 1)/(t + 1)))
/// leaves |x| <= tan(pi/8), where atan(x) = x + x z P(z)/Q(z), z = x^2, with the [5/5] Pade approximant of
/// (atan(x) - x)/(x z) (relative error 2.7e-17 at the end of the range; scripts/atan_coefficients.py derives it).
/// P and Q go by Estrin's scheme (three levels of independent products instead of a chain of five). Written without
/// branches so that a pack takes it lane by lane; a plain double skips the reduction's division where it divides by
/// 1, which changes no bit (t/1 = t) and saves its latency in the single evaluation.
/// Why our own: glibc's atan has no pack form, and a pack must round as the single evaluation does.
template <class T>
inline T atanNonNegative(T t) {
  if constexpr (lanesOf<T>() == 1) {
    return t <= kAtanSmallLimit ? atanSmall(t) : atanGeneral(t);
  } else {
    // A pack computes the form its lanes need, both only when its lanes straddle the limit.
    const auto small = t <= splat<T>(kAtanSmallLimit);
    if (!anyOf(~small)) return atanSmall(t);
    if (!anyOf(small)) return atanGeneral(t);
    return small ? atanSmall(t) : atanGeneral(t);
  }
}

/// The largest power of two below @p n (n >= 2).
constexpr int powerOfTwoBelow(int n) { return n <= 2 ? 1 : 2 * powerOfTwoBelow((n + 1) / 2); }
constexpr int log2Of(int n) { return n <= 1 ? 0 : 1 + log2Of(n / 2); }

/// c[kLo] + c[kLo+1] x + ... + c[kLo+kCount-1] x^(kCount-1): the lower half (kHalf coefficients, a power of two) plus
/// x^kHalf times the upper half, each split again; @p powers holds x, x^2, x^4, ... Compile-time recursion, so the
/// whole tree is straight code with no array in memory.
template <int kLo, int kCount, int N, class T>
inline T estrinRange(const double (&c)[N], const T* powers) {
  if constexpr (kCount == 1) {
    return splat<T>(c[kLo]);
  } else {
    constexpr int kHalf = powerOfTwoBelow(kCount);
    return estrinRange<kLo, kHalf>(c, powers) + powers[log2Of(kHalf)] * estrinRange<kLo + kHalf, kCount - kHalf>(c, powers);
  }
}

/// c[0] + c[1] x + ... + c[N-1] x^(N-1) by Estrin's scheme: pairs c[2i] + c[2i+1] x, then pairs of those with x^2,
/// then with x^4, ...: a tree about log2(N) products deep where Horner's rule is a chain of N - 1.
template <int N, class T>
inline T estrin(const double (&c)[N], T x) {
  static_assert(N >= 1, "a polynomial has a coefficient");
  T powers[log2Of(N) + 1];
  powers[0] = x;
  for (int k = 1; k <= log2Of(N); ++k) powers[k] = powers[k - 1] * powers[k - 1];
  return estrinRange<0, N>(c, powers);
}

/// sinCosSmall's coefficients: 1/(2k+1)!, k = 0..11, for sin x / x, and 1/(2k)! for cos x.
inline constexpr double kSinTaylor[12] = {
    1.0, 1.0 / 6.0, 1.0 / 120.0, 1.0 / 5040.0, 1.0 / 362880.0, 1.0 / 39916800.0, 1.0 / 6227020800.0,
    1.0 / 1307674368000.0, 1.0 / 355687428096000.0, 1.0 / 121645100408832000.0, 1.0 / 51090942171709440000.0,
    1.0 / 25852016738884976640000.0};
inline constexpr double kCosTaylor[12] = {
    1.0, 1.0 / 2.0, 1.0 / 24.0, 1.0 / 720.0, 1.0 / 40320.0, 1.0 / 3628800.0, 1.0 / 479001600.0, 1.0 / 87178291200.0,
    1.0 / 20922789888000.0, 1.0 / 6402373705728000.0, 1.0 / 2432902008176640000.0, 1.0 / 1124000727777607680000.0};

/// cos(x) and sin(x) for 0 <= x <= pi/2 by their Taylor series to x^22 and x^23 (the first term left out is below
/// 2e-18 there), as polynomials in z = x^2 by Estrin's scheme: pairs of coefficients, then z^2, z^4 and z^8 combine
/// them, a tree five products deep instead of Horner's chain of eleven. For x <= 1/8 (joint 1's base half angle stays
/// below 0.03 rad in the validated range) the series stop at x^10 and x^11 (the first term left out, x^12/12!, is
/// below 1e-19 there): half the work. Absolute error below 2 ulp of 1 (test: SinCosSmall). Shared by the single
/// evaluation and the batch kernel for joint 1's base half angle (docs/MODEL.md stage 5), so that both round it alike.
constexpr double kSinCosShortLimit = 0.125;
template <class T>
inline void sinCosSmall(T x, T& cos_x, T& sin_x) {
  const T z = x * x;
  const T z2 = z * z;
  const T z4 = z2 * z2;
  // a_k (-z)^k summed over k = 0..11 (or 0..5), with a_k = 1/(2k+1)! for sin x / x and 1/(2k)! for cos x; the signs are
  // folded into the pairs a_2j - a_2j+1 z.
  auto pairs = [z](const double* a, T* p, int count) {
    for (int j = 0; j < count; ++j) p[j] = splat<T>(a[2 * j]) - z * splat<T>(a[2 * j + 1]);
  };
  auto shortSeries = [&](const double* a) {
    T p[3];
    pairs(a, p, 3);
    return (p[0] + z2 * p[1]) + z4 * p[2];
  };
  auto longSeries = [&](const double* a) {
    T p[6];
    pairs(a, p, 6);
    const T z8 = z4 * z4;
    return ((p[0] + z2 * p[1]) + z4 * (p[2] + z2 * p[3])) + z8 * (p[4] + z2 * p[5]);
  };
  bool all_short, any_short;
  if constexpr (lanesOf<T>() == 1) {
    all_short = any_short = x <= kSinCosShortLimit;
  } else {
    const auto short_lane = x <= splat<T>(kSinCosShortLimit);
    all_short = !anyOf(~short_lane);
    any_short = anyOf(short_lane);
  }
  if (all_short) {
    sin_x = x * shortSeries(kSinTaylor);
    cos_x = shortSeries(kCosTaylor);
  } else if (!any_short) {
    sin_x = x * longSeries(kSinTaylor);
    cos_x = longSeries(kCosTaylor);
  } else {
    // A pack that straddles the limit: each lane as the single evaluation would take it.
    const auto short_lane = x <= splat<T>(kSinCosShortLimit);
    sin_x = short_lane ? x * shortSeries(kSinTaylor) : x * longSeries(kSinTaylor);
    cos_x = short_lane ? shortSeries(kCosTaylor) : longSeries(kCosTaylor);
  }
}

}  // namespace
}  // namespace pneumatic_finger

#pragma GCC diagnostic pop
