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

/// Stages 2 and 3 together (docs/MODEL.md) for small energy groups: with s = sqrt(g/3) <= 1/20, the stretch excess
/// delta and the bulge h as power series in s, delta = s (1 + s/3 - s^2/18 - ...) and h = L s (1 - s/6 + 11 s^2/18 - ...).
/// Both come from s at once, so the chain skips the cubic's Halley steps and the bulge's square root and division
/// (together about as long as the rest of the chain). The coefficients and their error are derived exactly by
/// scripts/wall_series.py: the terms left out are below 6e-21 (delta) and 1.3e-18 (h) relative, well below the
/// rounding of the sums (test: Stage23Series). The limit covers the calibrated finger to 3.4e5 Pa, beyond its
/// validated range (2 kg/cm^2) and the table's (3e5 Pa); above it the Halley steps answer.
constexpr double kStretchSeriesLimit = 0.05;
template <class T>
inline void stretchAndBulgeSeries(T s, double chamber_height_m, T& stretch_excess, T& bulge_m) {
  static constexpr double kStretch[13] = {1.0, 0.3333333333333333, -0.05555555555555555, -0.037037037037037035,
                                          0.023148148148148147, 0.00411522633744856, -0.009002057613168725,
                                          0.0013717421124828531, 0.0030423620637098003, -0.0015749631661840166,
                                          -0.0007487822613422751, 0.0009427198880026193, 5.518236619869374e-06};
  static constexpr double kBulge[19] = {1.0, -0.16666666666666666, 0.6111111111111112, -1.287037037037037,
                                        2.7453703703703702, -6.276748971193416, 15.046553497942387,
                                        -37.20413237311386, 94.16247880467917, -242.80790212366,
                                        635.6690019226617, -1685.1426906396948, 4514.487249626413,
                                        -12203.085460039309, 33241.729265522365, -91162.71356536484,
                                        251487.37246667803, -697407.7990546674, 1943046.0695171214};
  stretch_excess = s * estrin(kStretch, s);
  bulge_m = splat<T>(chamber_height_m) * (s * estrin(kBulge, s));
}

/// s^2 = g/3 = P (2 P_o + P) / (3 P_o mu), the series' argument squared, from the gauge pressure: one product chain
/// with the constant 1/(3 P_o mu) (@p inv_three_po_mu) instead of stage 1's two divisions.
template <class T>
inline T stretchSeriesArgumentSquared(T gauge_pa, double atmospheric_pa, double inv_three_po_mu) {
  return gauge_pa * (splat<T>(2.0 * atmospheric_pa) + gauge_pa) * splat<T>(inv_three_po_mu);
}

/// sqrt(h/(L s)) = 1 - s/12 + 29 s^2/96 - ... for s <= 1/20 (scripts/wall_series.py: the terms left out are below 5.1e-19
/// relative), so that stage 4's m = 2 sqrt(h c)/b = (2 sqrt(L c)/b) sqrt(s) sqrt(h/(L s)) needs no square root of h: only
/// sqrt(s), which runs beside the series instead of after them.
template <class T>
inline T bulgeRootSeries(T s) {
  static constexpr double kRoot[19] = {1.0, -0.08333333333333333, 0.3020833333333333, -0.6183449074074074,
                                       1.2755292727623457, -2.845288688753858, 6.709678011503076,
                                       -16.39469503080894, 41.11527568349895, -105.24696972359337,
                                       273.8998798651855, -722.5266941770849, 1927.6122829794456,
                                       -5192.046960708485, 14100.035206253755, -38564.81989420076,
                                       106137.06196593269, -293717.7641003618, 816800.8828791904};
  return estrin(kRoot, s);
}

/// Stage 4's first guess of v = (1 + tan^2 theta)^(1/4) - 1 (docs/MODEL.md; stages.cpp explains the forms), from
/// D = num/den: below D = 1 the [1/1] Pade form of v(D) times the gap's first-order factor (1 - m D/2) where that is
/// positive, written over one division with num and den (D's own division runs beside it, not before it); above, v(D)
/// itself, (D^2)/((r + 1)(sqrt(r) + 1)) with r = sqrt(1 + D^2). A pack computes the second form only when a lane needs it.
template <class T>
inline T quarterPowerStart(T num, T den, T d, T m) {
  const T one = splat<T>(1.0);
  const T num_sq = num * num;
  const T den_sq_pade = den * den + splat<T>(0.375) * num_sq;
  const T shrunk = den - splat<T>(0.5) * m * num;  // den (1 - m D/2)
  const auto shrink = shrunk > splat<T>(0.0);
  const T small_d = (splat<T>(0.25) * num_sq * (shrink ? shrunk : den)) / (den * den_sq_pade);
  const auto below = d < one;
  if (!anyOf(notOf(below))) return small_d;
  const T r = sqrtOf(one + d * d);
  const T large_d = d * d / ((r + one) * (sqrtOf(r) + one));
  return below ? small_d : large_d;
}

/// Stage 4's solve where the walls touch (0 < D <= 1e6, m > 0; the rare rest stays in stages.cpp): safeguarded Halley
/// steps on Q(v) = v (4 + 6v + 4v^2 + v^3) - (D - m v)^2 from @p v (stages.cpp explains Q, the bracket and the stopping
/// rule), then t = D - m v, theta = atan(t), cos theta = 1/w^2 and sin theta = t cos theta, w = 1 + v. Lanes outside
/// @p active take no step, and their outputs mean nothing: the caller selects. Shared by the single evaluation and the
/// batch kernel: a lane stops where the single evaluation stops, and a pack goes on until its last lane has stopped.
/// @return the steps taken (at least 1).
template <class T, class M>
inline int wallHalfAngle(T d, T m, T v, M active, T& rad, T& cos_half, T& sin_half, T& tan_half) {
  const T zero = splat<T>(0.0), one = splat<T>(1.0);
  T lo = zero, hi = d / m;
  v = v < hi ? v : splat<T>(0.5) * hi;
  int steps = 0;
  for (; steps < 64 && anyOf(active); ++steps) {
    const T w = one + v;
    const T tv = d - m * v;
    // Q by Estrin's pairs: v ((4 + 6v) + v^2 (4 + v)).
    const T q = v * ((splat<T>(4.0) + splat<T>(6.0) * v) + (v * v) * (splat<T>(4.0) + v)) - tv * tv;
    active = active & (q != zero);
    const auto above = q > zero;
    hi = active & above ? v : hi;
    lo = active & notOf(above) ? v : lo;
    const T qp = splat<T>(4.0) * w * w * w + splat<T>(2.0) * m * tv;
    const T qpp = splat<T>(12.0) * w * w - splat<T>(2.0) * m * m;
    const T step = splat<T>(2.0) * q * qp / (splat<T>(2.0) * qp * qp - q * qpp);
    T next = v - step;
    const auto halley = (next >= lo) & (next <= hi);
    next = halley ? next : splat<T>(0.5) * (lo + hi);
    const T moved = next - v < zero ? v - next : next - v;
    v = active ? next : v;
    // A Halley step of size s leaves an error of order s^3; t = D - m v needs m * error < ulp(t).
    const T d_mv = d - m * v, v_tiny = v + splat<T>(1e-300);
    const auto converged = halley & (moved * moved * moved * (one + m) <=
                                     splat<T>(1e-17) * (one < d_mv ? one : d_mv) * (one < v_tiny ? one : v_tiny));
    const auto bracketed = hi - lo <= splat<T>(4.0 * __DBL_EPSILON__) * hi;
    active = active & notOf(converged) & notOf(bracketed);
  }
  const T t = d - m * v;
  const T w = one + v;
  tan_half = t;
  rad = atanNonNegative(t);
  cos_half = one / (w * w);  // w is solved to well below an ulp of v: no square root needed
  sin_half = t * cos_half;
  return steps < 1 ? 1 : steps;
}

/// Stages 2-3 of one wall where their series hold (P >= 0 and s = sqrt(g/3) <= kStretchSeriesLimit): the stretch
/// excess, the bulge, and, where the walls touch (h > c), stage 4's m = 2 sqrt(h c)/b from the series too
/// (bulgeRootSeries: no square root of h after the series; else m = 0). Written once for solveWall (stages.cpp) and
/// for the model's evaluation (finger_model.cpp), which inlines it so that nothing passes through memory between the
/// stages.
/// @return false beyond the series' limit (or for P < 0, NaN), where stages.cpp runs the stages one by one
inline bool wallStagesBySeries(double gauge_pa, double atmospheric_pa, double shear_modulus_pa, double chamber_height_m,
                               double gap_m, double two_over_b, double& stretch_excess, double& bulge_m, double& m) {
  const double s_sq =
      stretchSeriesArgumentSquared(gauge_pa, atmospheric_pa, 1.0 / (3.0 * atmospheric_pa * shear_modulus_pa));
  if (!(gauge_pa >= 0.0 && s_sq <= kStretchSeriesLimit * kStretchSeriesLimit)) return false;
  const double s = __builtin_sqrt(s_sq);
  stretchAndBulgeSeries(s, chamber_height_m, stretch_excess, bulge_m);
  m = bulge_m > gap_m
          ? (__builtin_sqrt(chamber_height_m * gap_m) * two_over_b) * (__builtin_sqrt(s) * bulgeRootSeries(s))
          : 0.0;
  return true;
}

/// Stage 4 of one touching wall in its usual form (H = 2h/b < 1e200, m > 0, D <= 1e6): D = H (H - 2k)/(H + m), then
/// wallHalfAngle from quarterPowerStart (stages.cpp, halfAngleOfWall, explains the forms). Shared like
/// wallStagesBySeries.
/// @return false, writing nothing, for the rare forms (no gap, a huge bulge), which halfAngleOfWall takes
inline bool usualWallHalfAngle(double bulge_m, double gap_m, double two_over_b, double m, double& rad,
                               double& cos_half, double& sin_half, double& tan_half, int& iterations) {
  const double big_h = bulge_m * two_over_b;
  // (h c underflows to 0 only for c < 1e-154 m, where m < 1e-75 and dropping it changes nothing.)
  const double num = big_h * ((bulge_m - gap_m) * two_over_b), den = big_h + m;
  const double d = num / den;
  if (!(big_h < 1e200 && m > 0.0 && d <= 1e6)) return false;
  iterations = wallHalfAngle(d, m, quarterPowerStart(num, den, d, m), true, rad, cos_half, sin_half, tan_half);
  return true;
}

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
  static constexpr double kSin[12] = {1.0,
                                      1.0 / 6.0,
                                      1.0 / 120.0,
                                      1.0 / 5040.0,
                                      1.0 / 362880.0,
                                      1.0 / 39916800.0,
                                      1.0 / 6227020800.0,
                                      1.0 / 1307674368000.0,
                                      1.0 / 355687428096000.0,
                                      1.0 / 121645100408832000.0,
                                      1.0 / 51090942171709440000.0,
                                      1.0 / 25852016738884976640000.0};
  static constexpr double kCos[12] = {1.0,
                                      1.0 / 2.0,
                                      1.0 / 24.0,
                                      1.0 / 720.0,
                                      1.0 / 40320.0,
                                      1.0 / 3628800.0,
                                      1.0 / 479001600.0,
                                      1.0 / 87178291200.0,
                                      1.0 / 20922789888000.0,
                                      1.0 / 6402373705728000.0,
                                      1.0 / 2432902008176640000.0,
                                      1.0 / 1124000727777607680000.0};
  bool all_short, any_short;
  if constexpr (lanesOf<T>() == 1) {
    all_short = any_short = x <= kSinCosShortLimit;
  } else {
    const auto short_lane = x <= splat<T>(kSinCosShortLimit);
    all_short = !anyOf(~short_lane);
    any_short = anyOf(short_lane);
  }
  if (all_short) {
    sin_x = x * shortSeries(kSin);
    cos_x = shortSeries(kCos);
  } else if (!any_short) {
    sin_x = x * longSeries(kSin);
    cos_x = longSeries(kCos);
  } else {
    // A pack that straddles the limit: each lane as the single evaluation would take it.
    const auto short_lane = x <= splat<T>(kSinCosShortLimit);
    sin_x = short_lane ? x * shortSeries(kSin) : x * longSeries(kSin);
    cos_x = short_lane ? shortSeries(kCos) : longSeries(kCos);
  }
}

/// Joint 1 of identical chambers (docs/MODEL.md stage 5): q_1 = theta_0 + theta with theta_0 = s0 theta (the passive
/// base segment's face); with s0 = 0, q_1 = theta exactly.
template <class T>
inline T firstJointAngle(double base_wall_share, T theta) {
  return base_wall_share == 0.0 ? theta : base_wall_share * theta + theta;
}

/// Up to this tan(theta), joint 1's direction comes from its series (FirstJointSeries, stages.hpp).
constexpr double kFirstJointSeriesLimit = 0.125;

/// Joint 1 of identical chambers: q_1 (firstJointAngle) and the direction of segment 1, e^(i q_1) = e^(i (1 + s0)
/// theta). With s0 = 0 nothing is computed: the direction is theta's own, exactly. Up to tan(theta) = 1/8 (7 degrees:
/// the calibrated finger's validated range) it is @p series in t (stages.hpp); above, the base face's sine and cosine
/// rotate theta's
/// (a pack takes the form each lane needs, both only when its lanes straddle the limit).
/// @return q_1
template <class T>
inline T firstJoint(double base_wall_share, const FirstJointSeries& series, T theta, T tan_half, T cos_half,
                    T sin_half, T& first_c, T& first_s) {
  if (base_wall_share == 0.0) {
    first_c = cos_half;
    first_s = sin_half;
    return theta;
  }
  auto fromSeries = [&](T& c, T& s) {
    const T z = tan_half * tan_half;
    c = estrin(series.cos_c, z);
    s = tan_half * estrin(series.sin_c, z);
  };
  auto fromFace = [&](T& c, T& s) {
    T c0, s0;
    sinCosSmall(base_wall_share * theta, c0, s0);
    c = c0 * cos_half - s0 * sin_half;
    s = s0 * cos_half + c0 * sin_half;
  };
  bool all_series, any_series;
  if constexpr (lanesOf<T>() == 1) {
    all_series = any_series = tan_half <= kFirstJointSeriesLimit;
  } else {
    const auto lane = tan_half <= splat<T>(kFirstJointSeriesLimit);
    all_series = !anyOf(notOf(lane));
    any_series = anyOf(lane);
  }
  if (all_series) {
    fromSeries(first_c, first_s);
  } else if (!any_series) {
    fromFace(first_c, first_s);
  } else {
    T sc, ss, fc, fs;
    fromSeries(sc, ss);
    fromFace(fc, fs);
    const auto lane = tan_half <= splat<T>(kFirstJointSeriesLimit);
    first_c = lane ? sc : fc;
    first_s = lane ? ss : fs;
  }
  return firstJointAngle(base_wall_share, theta);
}

/// Stage 6 for identical chambers (docs/MODEL.md): the backbone's points 2..N+1 (point 0 is the mount, point 1 the end
/// of the base segment, (Z_0, 0)). Segment n points along q_1 + 2 (n - 1) theta, that is e^(i q_1) r^(n-1) with
/// r = e^(2 i theta), so point n + 1 is (Z_0, 0) + e^(i q_1) S_n with S_n = sum_(j < n) Z_(j+1) r^j: the backbone in
/// segment 1's frame, turned once. S needs only cos and sin of theta, which the solve has before theta itself (they
/// come from w, theta from the arctangent of t), so its complex products run beside the arctangent and joint 1's
/// direction, and one rotation per point is all that waits for those. The powers of r: r, r^2, r^3 = r r^2, and every
/// later one from the one four before it and r^4, a chain 2 + (N - 4)/4 products long instead of N - 1. Shared by the
/// single evaluation and the batch kernel, so that both round alike.
/// @tparam kChambers the chamber count when known at compile time (the loops then unroll into straight code), else 0
/// @param first_c, first_s e^(i q_1), from firstJoint (or the table's polynomials)
/// @param cos_half, sin_half cos and sin of theta
/// @param power_c, power_s scratch for N powers of r
/// @param[out] x, y the points' coordinates, point 2 + j at x[j * stride], y[j * stride] (no element reached through
/// both, nor through the scratch: hence __restrict)
template <int kChambers, class T>
inline void uniformPoints(T first_c, T first_s, T cos_half, T sin_half, int chamber_count,
                          double base_segment_length_m, const double* __restrict segment_length_m,
                          T* __restrict power_c, T* __restrict power_s, T* __restrict x, T* __restrict y, int stride) {
  const int n = kChambers > 0 ? kChambers : chamber_count;
  // r = e^(2 i theta): cos 2 theta as a product, which does not cancel near pi/4.
  const T r1_c = (cos_half - sin_half) * (cos_half + sin_half);
  const T r1_s = splat<T>(2.0) * sin_half * cos_half;
  const T r2_c = (r1_c - r1_s) * (r1_c + r1_s);
  const T r2_s = splat<T>(2.0) * r1_s * r1_c;
  const T r4_c = (r2_c - r2_s) * (r2_c + r2_s);
  const T r4_s = splat<T>(2.0) * r2_s * r2_c;
  const T head_c[4] = {splat<T>(1.0), r1_c, r2_c, r1_c * r2_c - r1_s * r2_s};
  const T head_s[4] = {splat<T>(0.0), r1_s, r2_s, r1_s * r2_c + r1_c * r2_s};
#pragma GCC unroll 4
  for (int j = 0; j < (n < 4 ? n : 4); ++j) {
    power_c[j] = head_c[j];
    power_s[j] = head_s[j];
  }
#pragma GCC unroll 64
  for (int j = 4; j < n; ++j) {
    power_c[j] = power_c[j - 4] * r4_c - power_s[j - 4] * r4_s;
    power_s[j] = power_s[j - 4] * r4_c + power_c[j - 4] * r4_s;
  }
  const T x0 = splat<T>(base_segment_length_m);
  T sx = splat<T>(0.0), sy = splat<T>(0.0);
#pragma GCC unroll 64
  for (int j = 0; j < n; ++j) {
    sx += segment_length_m[j] * power_c[j];
    sy += segment_length_m[j] * power_s[j];
    x[j * stride] = x0 + (first_c * sx - first_s * sy);
    y[j * stride] = first_s * sx + first_c * sy;
  }
}

}  // namespace
}  // namespace pneumatic_finger

#pragma GCC diagnostic pop
