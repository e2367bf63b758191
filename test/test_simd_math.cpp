// The math both the single evaluation and the batch kernels share (simd_math.hpp, joint_chain.hpp, table_kernel.hpp),
// against libquadmath's __float128: the arctangent of our own, joint 1's direction from tan(theta), the small-angle
// sine and cosine, and the table's polynomials in every instruction set this CPU runs.
#include <gtest/gtest.h>
#include <quadmath.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "pneumatic_finger/core/stages.hpp"
#include "../src/core/joint_chain.hpp"  // firstJoint and sinCosSmall (internal), tested directly
#include "../src/core/table_kernel.hpp"  // the table's polynomial variants (internal), tested directly

namespace pf = pneumatic_finger;

namespace {
bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
}  // namespace

// The atan of our own (simd_math.hpp), seen through the public halfAngle: at c = 0, eq 15 is h = (b/2) tan(theta),
// so theta is our atan of tan(theta) = D, which halfAngle forms as H (H - 0)/(H + 0) with H = 2h/b (= h for b = 2):
// D = (h h)/h in double. Against atanq (113-bit) over 300 decades, relative error within 1.5 ulp.
TEST(OwnArctangent, WithinOneAndAHalfUlpOfQuadPrecision) {
  const double b = 2.0;
  double worst_ulps = 0.0, worst_at = 0.0;
  for (double t = 1e-150; t < 1e150; t *= 1.0137) {
    for (double x : {t, 0.4142135623730950, 2.414213562373095, 1.0}) {
      const double got = pf::halfAngle(x, 0.0, b).rad;
      const double arg = (x * x) / x;  // what halfAngle hands to the arctangent
      const __float128 want = atanq(static_cast<__float128>(arg));
      const double ulp = std::nextafter(static_cast<double>(want), INFINITY) - static_cast<double>(want);
      const double ulps = static_cast<double>(fabsq(static_cast<__float128>(got) - want)) / ulp;
      if (ulps > worst_ulps) {
        worst_ulps = ulps;
        worst_at = x;
      }
    }
  }
  EXPECT_LE(worst_ulps, 1.5) << "at t = " << worst_at;
  // The ends: atan(t) = t for tiny t, atan(+inf) = pi/2 rounded.
  EXPECT_EQ(pf::halfAngle(1e-100, 0.0, b).rad, (1e-100 * 1e-100) / 1e-100);
  EXPECT_EQ(pf::halfAngle(1e199, 0.0, b).rad, static_cast<double>(acosq(-1) / 2));
}

namespace {
// The largest error of a (cos, sin) pair against libquadmath's of @p angle over the samples it is given, and where.
struct WorstCosSin {
  double error = 0.0, at = 0.0;
  void check(double x, double c, double s, __float128 angle) {
    const double e = std::max(static_cast<double>(fabsq(c - cosq(angle))), static_cast<double>(fabsq(s - sinq(angle))));
    if (e > error) error = e, at = x;
  }
};
}  // namespace

// Joint 1's direction from tan(theta) (stages.hpp, FirstJointSeries; joint_chain.hpp, firstJoint): cos and sin of
// (1 + s0) atan(t) against libquadmath's, up to the series' limit t = 1/8 and just above it (where the base face's sine
// and cosine answer), for inert, calibrated and fully turning faces.
TEST(FirstJointSeries, WithinTwoUlpOfQuadPrecision) {
  const double ulp_of_one = std::numeric_limits<double>::epsilon();
  for (double share : {0.0, 0.1, 0.31406024809341682, 0.5, 1.0}) {
    const pf::FirstJointSeries series = pf::firstJointSeries(share);
    WorstCosSin worst;
    auto check = [&](double t) {
      const __float128 q1 = (1 + static_cast<__float128>(share)) * atanq(static_cast<__float128>(t));
      // theta, cos and sin as the solve gives them (each rounded once), the direction from them.
      const __float128 theta_q = atanq(static_cast<__float128>(t));
      const double theta = static_cast<double>(theta_q);
      const double cos_half = static_cast<double>(cosq(theta_q)), sin_half = static_cast<double>(sinq(theta_q));
      double c = 0.0, s = 0.0;
      pf::firstJoint(share, series, theta, t, cos_half, sin_half, c, s);
      worst.check(t, c, s, q1);
    };
    for (double t = 1e-300; t < 0.2; t *= 1.01) check(t);
    for (int i = 0; i <= 20000; ++i) check(0.2 * i / 20000);
    for (int k = -20; k <= 20; ++k) check(0.125 + k * 1e-17);
    EXPECT_LE(worst.error, 2.0 * ulp_of_one) << "s0 = " << share << ", at t = " << worst.at;
  }
}

// The sine and cosine of joint 1's base half angle (simd_math.hpp, sinCosSmall: the short series up to 1/8, the long
// one up to pi/2) against libquadmath's: absolute error within 2 ulp of 1 over [0, pi/2] (the long series' alternating terms
// cost a little near pi/2, where x^2 = 2.5), both sides of the switch.
TEST(SinCosSmall, WithinTwoUlpOfQuadPrecision) {
  const double ulp_of_one = std::numeric_limits<double>::epsilon();
  WorstCosSin worst;
  auto check = [&](double x) {
    double c = 0.0, s = 0.0;
    pf::sinCosSmall(x, c, s);
    worst.check(x, c, s, x);
  };
  for (double x = 1e-300; x < 1.0; x *= 1.01) check(x);
  for (int i = 0; i <= 100000; ++i) check(1.5707963267948966 * i / 100000);
  for (int k = -20; k <= 20; ++k) check(0.125 + k * 1e-17);
  EXPECT_LE(worst.error, 2.0 * ulp_of_one) << "at x = " << worst.at;
  double c = 0.0, s = 0.0;
  pf::sinCosSmall(0.0, c, s);
  EXPECT_EQ(c, 1.0);
  EXPECT_EQ(s, 0.0);
}

// The table solver's polynomials (table_kernel.hpp), one variant per instruction set: the same bits in every variant
// this CPU runs, and each value within a few ulp of the polynomial evaluated in quad precision (Horner, __float128).
TEST(TablePolynomials, EveryVariantGivesTheSameBitsAndMatchesQuadPrecision) {
  std::vector<std::pair<const char*, pf::TablePolynomials>> variants;
  for (auto [name, set] : {std::pair{"generic", pf::InstructionSet::kGeneric},
                           std::pair{"avx2", pf::InstructionSet::kAvx2},
                           std::pair{"avx512", pf::InstructionSet::kAvx512}}) {
    if (const pf::SimdKernels* kernels = pf::simdKernels(set)) variants.emplace_back(name, kernels->table_polynomials);
  }
  ASSERT_FALSE(variants.empty()) << "the baseline instruction set always runs";
  std::mt19937_64 rng(20261124);
  std::uniform_real_distribution<double> coefficient(-1.0, 1.0), local(-1.0, 1.0);
  const double sentinel = -12345.0;
  for (int functions : {8, 16, 40}) {
    std::vector<double> row(static_cast<std::size_t>(8 * functions));
    // Coefficients that shrink with the power, as an interpolant's do, so that the sum is not all cancellation.
    for (int i = 0; i < 8; ++i) {
      for (int f = 0; f < functions; ++f) {
        row[static_cast<std::size_t>(i * functions + f)] = coefficient(rng) / (1 << i);
      }
    }
    // Every count of live functions in the last pack (the shape table writes 2 N + 1 of them into the state).
    for (int live = functions - 7; live <= functions; ++live) {
      for (int trial = 0; trial < 50; ++trial) {
        const double x = trial == 0 ? -1.0 : trial == 1 ? 1.0 : local(rng);
        std::vector<double> want(static_cast<std::size_t>(functions), sentinel);
        variants[0].second(row.data(), functions, live, x, want.data());
        for (int f = 0; f < functions; ++f) {
          if (f >= live) {
            EXPECT_TRUE(sameBits(want[static_cast<std::size_t>(f)], sentinel)) << "generic wrote past live: f = " << f;
            continue;
          }
          __float128 quad = 0;
          for (int i = 7; i >= 0; --i) quad = quad * x + row[static_cast<std::size_t>(i * functions + f)];
          // Estrin's scheme rounds each term c_i x^i at most 8 times (c7: c7 x, + c6, x^2, * x^2, + p45, x^4 (two),
          // * x^4, + the rest), so its error is at most 8 eps sum |c_i x^i| (to first order).
          double magnitude = 0.0;
          for (int i = 0; i < 8; ++i) {
            magnitude += std::fabs(row[static_cast<std::size_t>(i * functions + f)] * std::pow(x, i));
          }
          EXPECT_LE(std::fabs(static_cast<double>(quad - want[static_cast<std::size_t>(f)])),
                    8.0 * std::numeric_limits<double>::epsilon() * magnitude)
              << "f = " << f << ", x = " << x;
        }
        for (std::size_t v = 1; v < variants.size(); ++v) {
          std::vector<double> got(static_cast<std::size_t>(functions), sentinel);
          variants[v].second(row.data(), functions, live, x, got.data());
          for (int f = 0; f < functions; ++f) {
            // Past live the sentinel must survive: the same bits as generic's untouched entries.
            EXPECT_TRUE(sameBits(got[static_cast<std::size_t>(f)], want[static_cast<std::size_t>(f)]))
                << variants[v].first << ": f = " << f << ", live = " << live << ", x = " << x;
          }
        }
      }
    }
  }
}
