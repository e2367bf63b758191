// The table solver's polynomials (finger_model.cpp, buildTable), SIMD across functions: one segment's degree-7
// polynomials at one x, a pack of functions at a time. Compiled once per instruction set beside the batch kernel
// (batch_generic.cpp, batch_avx2.cpp, batch_avx512.cpp); the model picks the widest the CPU has. Every variant does
// the same operations in the same order as tableFunction (finger_model.cpp) and nothing fuses a multiply with an add
// (-ffp-contract=off), so all of them give the same bits (test/test_batch.cpp).
#pragma once

#include "simd_math.hpp"

namespace pneumatic_finger {

/// Functions per table row are padded to a multiple of this, so that every variant's packs are whole.
constexpr int kTablePackFunctions = 8;

/// One of the variants below.
using TablePolynomials = void (*)(const double* row, int functions, double x, double* out);

/// Writes function f's value at @p x into out[f] for f < @p functions (a multiple of kTablePackFunctions), where
/// coefficient i of function f is row[i * functions + f].
void tablePolynomialsGeneric(const double* row, int functions, double x, double* out);
void tablePolynomialsAvx2(const double* row, int functions, double x, double* out);
void tablePolynomialsAvx512(const double* row, int functions, double x, double* out);

namespace {  // NOLINT(build/namespaces): internal linkage per instruction set (simd_math.hpp)

typedef double Pack2 __attribute__((vector_size(16)));

/// Estrin's scheme, as tableFunction: pairs, then x^2 and x^4 combine them (three levels of independent products
/// instead of Horner's chain of seven).
template <class T>
inline void tablePolynomials(const double* row, int functions, double x, double* out) {
  constexpr int kLanes = lanesOf<T>();
  static_assert(kTablePackFunctions % kLanes == 0, "whole packs");
  const double x2 = x * x, x4 = x2 * x2;
  for (int f = 0; f < functions; f += kLanes) {
    auto c = [row, functions, f](int i) {
      T v;
      __builtin_memcpy(&v, row + i * functions + f, sizeof v);
      return v;
    };
    const T value =
        ((c(0) + c(1) * x) + (c(2) + c(3) * x) * x2) + ((c(4) + c(5) * x) + (c(6) + c(7) * x) * x2) * x4;
    __builtin_memcpy(out + f, &value, sizeof value);
  }
}

}  // namespace
}  // namespace pneumatic_finger
