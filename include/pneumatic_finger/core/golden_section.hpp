// Golden-section search for a minimum, written once for the contact rule's grazing touches (src/core/touch_search.hpp)
// and the calibration's profile of the shear modulus (src/calibration/solver.cpp).
#pragma once

namespace pneumatic_finger {

/// 1/phi = (sqrt(5) - 1)/2: each step keeps this share of the bracket, and one interior point of the last step.
constexpr double kGoldenRatioConjugate = 0.6180339887498949;

/// The better interior point of a golden-section search, and the function's value there.
struct GoldenMinimum {
  double x, value;
};

/// Shrinks [a, b] around a minimum of @p f, one new evaluation per step, for at most @p max_steps steps and while
/// keep_going(a, b, f1, f2) holds for the bracket and its two interior values. A tie keeps the left part.
template <class F, class KeepGoing>
GoldenMinimum goldenSection(F&& f, double a, double b, int max_steps, KeepGoing&& keep_going) {
  double x1 = b - kGoldenRatioConjugate * (b - a), x2 = a + kGoldenRatioConjugate * (b - a);
  double f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < max_steps && keep_going(a, b, f1, f2); ++i) {
    if (f1 <= f2) {
      b = x2, x2 = x1, f2 = f1;
      x1 = b - kGoldenRatioConjugate * (b - a);
      f1 = f(x1);
    } else {
      a = x1, x1 = x2, f1 = f2;
      x2 = a + kGoldenRatioConjugate * (b - a);
      f2 = f(x2);
    }
  }
  return f1 <= f2 ? GoldenMinimum{x1, f1} : GoldenMinimum{x2, f2};
}

}  // namespace pneumatic_finger
