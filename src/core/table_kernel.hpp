// The table solver's polynomials (chamber_table.cpp), SIMD across functions: one segment's degree-7
// polynomials at one x, a pack of functions at a time. Compiled once per instruction set beside the batch kernel
// (batch_generic.cpp, batch_avx2.cpp, batch_avx512.cpp); the model picks the widest the CPU has. Every variant does
// the same operations in the same order as tableFunction (chamber_table.hpp) and nothing fuses a multiply with an add
// (-ffp-contract=off), so all of them give the same bits (test/test_simd_math.cpp).
#pragma once

#include "simd_kernels.hpp"
#include "simd_math.hpp"

namespace pneumatic_finger {

/// Functions per table row are padded to a multiple of this, so that every variant's packs are whole.
constexpr int kTablePackFunctions = 8;

namespace {  // NOLINT(build/namespaces): internal linkage per instruction set (simd_math.hpp)

typedef double Pack2 __attribute__((vector_size(16)));

/// The first @p count lanes of @p value to out[0..count): one masked store where the instruction set has one.
template <class T>
inline void storeFirst(double* out, T value, int count) {
#if defined(__AVX512F__)
  if constexpr (lanesOf<T>() == 8) {
    _mm512_mask_storeu_pd(out, static_cast<__mmask8>((1u << count) - 1u), reinterpret_cast<__m512d>(value));
    return;
  }
#endif
#if defined(__AVX2__)
  if constexpr (lanesOf<T>() == 4) {
    const __m256i lane = _mm256_set_epi64x(3, 2, 1, 0);
    _mm256_maskstore_pd(out, _mm256_cmpgt_epi64(_mm256_set1_epi64x(count), lane), reinterpret_cast<__m256d>(value));
    return;
  }
#endif
  for (int i = 0; i < count; ++i) out[i] = value[i];
}

/// Estrin's scheme, as tableFunction: pairs, then x^2 and x^4 combine them (three levels of independent products
/// instead of Horner's chain of seven). Whole packs are stored whole; the last one only up to @p live.
template <class T>
inline void tablePolynomials(const double* row, int functions, int live, double x, double* out) {
  constexpr int kLanes = lanesOf<T>();
  static_assert(kTablePackFunctions % kLanes == 0, "whole packs");
  const double x2 = x * x, x4 = x2 * x2;
  for (int f = 0; f < live; f += kLanes) {
    auto c = [row, functions, f](int i) {
      T v;
      __builtin_memcpy(&v, row + i * functions + f, sizeof v);
      return v;
    };
    const T value =
        ((c(0) + c(1) * x) + (c(2) + c(3) * x) * x2) + ((c(4) + c(5) * x) + (c(6) + c(7) * x) * x2) * x4;
    if (live - f >= kLanes) {
      __builtin_memcpy(out + f, &value, sizeof value);
    } else {
      storeFirst(out + f, value, live - f);
    }
  }
}

}  // namespace
}  // namespace pneumatic_finger
