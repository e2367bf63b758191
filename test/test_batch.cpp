// FingerModel::evaluateMany: every batch path (scalar, generic packs, AVX2, AVX-512) answers, pressure by pressure,
// the bits FingerModel::evaluate answers; and the arctangent of our own (which both share) against libquadmath's.
#include <gtest/gtest.h>
#include <quadmath.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/stages.hpp"
#include "../src/core/joint_chain.hpp"  // firstJoint and sinCosSmall (internal), tested directly
#include "../src/core/table_kernel.hpp"  // the table's polynomial variants (internal), tested directly

namespace pf = pneumatic_finger;

namespace {

// Pressures a batch meets: the validated range, docs/MODEL.md's hard cases (near rest, around contact, the
// resolvent band, theta -> pi/2 up to the rare branches), vacuum and refused values, in an order that puts every kind
// in every lane of a pack, and a count that leaves the last pack partly filled.
std::vector<double> batchPressures(const pf::FingerModel& model) {
  std::vector<double> p;
  for (int i = 0; i <= 400; ++i) p.push_back(196133.0 * i / 400);
  for (double x = 1e-12; x < 10; x *= 7) p.push_back(x);
  const double pc = model.contactGaugePa();
  for (int k = 1; k <= 16; ++k) {
    p.push_back(pc * (1 - std::pow(10.0, -k)));
    p.push_back(pc * (1 + std::pow(10.0, -k)));
  }
  p.push_back(pc);
  p.push_back(std::nextafter(pc, 0.0));
  p.push_back(std::nextafter(pc, INFINITY));
  for (double e = 5.0; e <= 300.0; e += 0.37) p.push_back(std::pow(10.0, e));  // through g > 1e30 and the big bulge
  for (double x : {-1.0, -1e5, -0.0, 0.0, std::numeric_limits<double>::quiet_NaN(), double(INFINITY),
                   -double(INFINITY), std::numeric_limits<double>::max(), std::numeric_limits<double>::denorm_min()}) {
    p.push_back(x);
  }
  // Packs whose lanes straddle a limit where the shared arithmetic switches form (simd_math.hpp): the arctangent's and
  // joint 1's direction's (both at tan(theta) = 1/8) and joint 1's base-face sine and cosine (s0 theta = 1/8, above
  // it), alternately just below and just above it.
  const pf::FingerParameters& params = model.parameters();
  const double turns = 2 * params.chamber_count - 1 + params.base_wall_share;
  std::vector<double> limits = {std::atan(0.125)};
  if (params.base_wall_share > 0.0 && 0.125 / params.base_wall_share < 1.5) limits.push_back(0.125 / params.base_wall_share);
  for (double theta : limits) {
    for (int k = 1; k <= 12; ++k) {
      for (double side : {-1.0, 1.0}) {
        double gauge = 0.0;
        std::string why;
        if (model.gaugeForTipAngle(turns * theta * (1.0 + side * k * 1e-9), 1e300, gauge, why)) p.push_back(gauge);
      }
    }
  }
  // ... and the series of stages 2-3 (s = sqrt(g/3) = 1/20, at P (2 P_o + P) = 3 P_o mu / 400).
  const double po = params.atmospheric_pressure_pa, mu = params.shear_modulus_pa[0];
  const double at_series_limit = std::sqrt(po * po + 3.0 * po * mu * 0.05 * 0.05) - po;
  for (int k = 1; k <= 12; ++k) {
    for (double side : {-1.0, 1.0}) p.push_back(at_series_limit * (1.0 + side * std::pow(10.0, -k - 3)));
  }
  p.push_back(std::nextafter(at_series_limit, 0.0));
  p.push_back(std::nextafter(at_series_limit, INFINITY));
  if (p.size() % 8 == 0) p.push_back(12345.0);
  return p;
}

using Rows = pf::BatchBuffers;

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Compares row i of a batch with evaluate() on a fresh model (no cache in play); returns how many values differ.
int compareRow(const pf::FingerModel& single, pf::FingerWorkspace& single_ws, const Rows& rows, std::size_t i,
               double gauge_pa, const std::string& what) {
  const int n = single.chamberCount();
  const auto un = static_cast<std::size_t>(n);
  const pf::FingerState& s = single.evaluate(gauge_pa, single_ws);
  int differ = 0;
  auto check = [&](double got, double want, const char* field, std::size_t k) {
    if (!sameBits(got, want)) {
      if (++differ <= 3) {
        ADD_FAILURE() << what << ": P = " << gauge_pa << " Pa, " << field << "[" << k << "] = " << got
                      << ", evaluate() gives " << want;
      }
    }
  };
  const pf::EvaluationStatus want = !std::isfinite(gauge_pa) ? pf::EvaluationStatus::kNotFinite : s.status;
  if (want == pf::EvaluationStatus::kNotFinite || want == pf::EvaluationStatus::kSolverFailure) {
    // Refused, or no answer (the paper's solver at some pressures): NaN throughout, where evaluate() keeps its
    // previous state.
    EXPECT_EQ(rows.status[i], static_cast<int>(want)) << what;
    for (std::size_t k = 0; k < un; ++k) EXPECT_TRUE(std::isnan(rows.half_angle_rad[i * un + k])) << what;
    for (std::size_t k = 0; k < 2 * (un + 2); ++k) EXPECT_TRUE(std::isnan(rows.backbone_m[i * 2 * (un + 2) + k]));
    EXPECT_TRUE(std::isnan(rows.tip_angle_rad[i]));
    return 0;
  }
  EXPECT_EQ(rows.status[i], static_cast<int>(s.status)) << what << " at P = " << gauge_pa;
  for (std::size_t k = 0; k < un; ++k) {
    const auto e = static_cast<Eigen::Index>(k);
    check(rows.stretch[i * un + k], s.stretch[e], "stretch", k);
    check(rows.bulge_m[i * un + k], s.bulge_m[e], "bulge_m", k);
    check(rows.half_angle_rad[i * un + k], s.half_angle_rad[e], "half_angle_rad", k);
    check(rows.joint_angle_rad[i * un + k], s.joint_angle_rad[e], "joint_angle_rad", k);
  }
  for (std::size_t k = 0; k < 2 * (un + 2); ++k) {
    check(rows.backbone_m[i * 2 * (un + 2) + k], s.backbone_m.data()[k], "backbone_m", k);
  }
  check(rows.tip_angle_rad[i], s.tip_angle_rad, "tip_angle_rad", 0);
  return differ;
}

void expectEveryPathMatchesEvaluate(const pf::FingerParameters& params, pf::SolverKind solver) {
  pf::ModelOptions options;
  options.solver = solver;
  pf::FingerModel batch(params, options);
  pf::FingerWorkspace batch_ws(batch);
  const std::vector<double> pressures = batchPressures(batch);
  int paths_run = 0;
  for (pf::BatchPath path : {pf::BatchPath::kBest, pf::BatchPath::kScalar, pf::BatchPath::kGeneric,
                             pf::BatchPath::kAvx2, pf::BatchPath::kAvx512}) {
    if (!pf::batchPathAvailable(path)) continue;  // this CPU lacks it; the generic pack runs the same code
    ++paths_run;
    Rows rows(pressures.size(), params.chamber_count);
    batch.evaluateMany(pressures.data(), pressures.size(), rows.outputs(), batch_ws, path);
    int differ = 0;
    for (std::size_t i = 0; i < pressures.size(); ++i) {
      pf::FingerModel single(params, options);
      pf::FingerWorkspace single_ws(single);
      differ += compareRow(single, single_ws, rows, i, pressures[i], std::string(pf::batchPathName(path)) + "/" +
                                                          pf::solverName(solver));
    }
    EXPECT_EQ(differ, 0) << pf::batchPathName(path) << ": values that differ from evaluate()";
  }
  EXPECT_GE(paths_run, 3);
  // The batch neither reads nor writes the workspace's cached state.
  EXPECT_EQ(batch_ws.computationCount(), 0);
}

}  // namespace

TEST(Batch, EveryPathAnswersTheBitsOfEvaluateForIdenticalChambers) {
  expectEveryPathMatchesEvaluate(pf::FingerParameters::defaults(), pf::SolverKind::kRobust);
}

TEST(Batch, OtherChamberCountsAndSegmentLengths) {
  // 1 chamber (no direction product at all), 3, 9 and 33 (powers r^2..r^32 of the direction tree), unequal lengths.
  for (int n : {1, 3, 9, 33}) {
    pf::RawParameterMap raw;
    pf::parseParameterAssignment("chamber_count=" + std::to_string(n), raw);
    std::string lengths = "segment_length_m=[";
    for (int i = 0; i < n; ++i) lengths += (i ? "," : "") + std::to_string(0.01 * (1.0 + 0.1 * i));
    pf::parseParameterAssignment(lengths + "]", raw);
    const pf::FingerParameters p = pf::FingerParameters::fromRaw(raw);
    SCOPED_TRACE("N = " + std::to_string(n));
    expectEveryPathMatchesEvaluate(p, pf::SolverKind::kRobust);
  }
}

TEST(Batch, TurningBaseFace) {
  pf::RawParameterMap raw;
  raw["base_wall_share"] = {{0.3}, false};
  expectEveryPathMatchesEvaluate(pf::FingerParameters::fromRaw(raw), pf::SolverKind::kRobust);
  raw["base_wall_share"] = {{1.0}, false};
  expectEveryPathMatchesEvaluate(pf::FingerParameters::fromRaw(raw), pf::SolverKind::kRobust);
}

TEST(Batch, UnequalChambersAndOtherSolversGoOneAtATime) {
  pf::FingerParameters unequal = pf::FingerParameters::defaults();
  unequal.chamber_gap_m[3] *= 1.5;
  expectEveryPathMatchesEvaluate(unequal, pf::SolverKind::kRobust);
  expectEveryPathMatchesEvaluate(pf::FingerParameters::defaults(), pf::SolverKind::kTable);
  expectEveryPathMatchesEvaluate(pf::FingerParameters::defaults(), pf::SolverKind::kPaper);
}

TEST(Batch, ZeroGapTakesTheSingleEvaluationsRareBranch) {
  pf::FingerParameters p = pf::FingerParameters::defaults();
  p.chamber_gap_m.assign(p.chamber_gap_m.size(), 0.0);
  expectEveryPathMatchesEvaluate(p, pf::SolverKind::kRobust);
}

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
