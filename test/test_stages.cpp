// Each stage of docs/MODEL.md, and the whole finger, against the quad-precision reference over a dense sweep.
#include <gtest/gtest.h>

#include <cmath>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/stages.hpp"
#include "test_support.hpp"

namespace pf = pneumatic_finger;
using pf_test::absError;

namespace {

const pf::FingerParameters kPaper = pf::FingerParameters::defaults();
reference::ChamberGeometry paperChamber() { return pf_test::chambersOf(kPaper)[0]; }

// 0 to 5 kg/cm^2 (2.5 times the validated range) linearly, plus 1e-3 Pa .. 5e5 Pa logarithmically.
const std::vector<double> kSweep = pf_test::pressureSweep(5 * 98066.5, 400, 20);

}  // namespace

TEST(Stage1EnergyGroup, MatchesReferenceToRelativeUlps) {
  for (double p : kSweep) {
    const double got = pf::energyGroup(p, kPaper.atmospheric_pressure_pa, kPaper.shear_modulus_pa[0]);
    const double want = reference::chamberChain(p, kPaper.atmospheric_pressure_pa, paperChamber()).energy_group;
    // Four roundings in the library plus the reference's final one: at most 5 half-ulps.
    EXPECT_LE(absError(got, want), 5 * 0x1p-53 * want) << "P = " << p;
  }
}

TEST(Stage1EnergyGroup, ZeroAndVacuumGiveZero) {
  EXPECT_EQ(pf::energyGroup(0.0, 101325, 2e8), 0.0);
  EXPECT_EQ(pf::energyGroup(-5e4, 101325, 2e8), 0.0);
}

TEST(Stage2Stretch, ExcessMatchesReferenceToRelativeUlps) {
  for (double p : kSweep) {
    const auto want = reference::chamberChain(p, kPaper.atmospheric_pressure_pa, paperChamber());
    const double got = pf::stretchExcess(want.energy_group);
    EXPECT_LE(absError(got, want.stretch_excess), 4e-16 * want.stretch_excess) << "P = " << p;
  }
}

TEST(Stage2Stretch, SolvesTheCubicOverTwentyDecadesOfG) {
  // lambda^3 - (g + 3) lambda + 2 = 0 <=> delta^2 (3 + delta) = g (1 + delta); check the residual relative
  // to the size of the terms, from g = 1e-30 to g = 1e30.
  for (double e = -30; e <= 30; e += 0.25) {
    const double g = std::pow(10.0, e);
    const double d = pf::stretchExcess(g);
    const double lhs = d * d * (3 + d), rhs = g * (1 + d);
    EXPECT_LE(std::fabs(lhs - rhs), 8e-16 * rhs) << "g = " << g;
  }
}

TEST(Stage3Bulge, MatchesReference) {
  for (double p : kSweep) {
    const auto want = reference::chamberChain(p, kPaper.atmospheric_pressure_pa, paperChamber());
    const double got = pf::bulge(pf::stretchExcess(want.energy_group), kPaper.chamber_height_m[0]);
    // Five roundings (delta's own, 2 + delta, the product, the square root, the quotient): at most ~3.6 ulp.
    EXPECT_LE(absError(got, want.bulge_m), 8e-16 * want.bulge_m) << "P = " << p;
  }
}

TEST(Stage23Series, ChainMatchesReferenceOnBothSidesOfTheSeriesLimit) {
  // solveWall takes stages 2-3 from their power series in s = sqrt(g/3) up to s = 1/20 (wall_chain.hpp), stage by stage
  // above: both must give the reference's stretch and bulge to a few ulp. The limit is at P = 3.4e5 Pa for this finger.
  const double po = kPaper.atmospheric_pressure_pa, mu = kPaper.shear_modulus_pa[0];
  const double limit_pa = std::sqrt(po * po + 3.0 * po * mu * 0.05 * 0.05) - po;
  std::vector<double> pressures = kSweep;
  for (int k = 1; k <= 12; ++k) {
    pressures.push_back(limit_pa * (1 - std::pow(10.0, -k)));
    pressures.push_back(limit_pa * (1 + std::pow(10.0, -k)));
  }
  // Up to three times the limit's pressure (s = 0.09), where the series, were it taken, would miss by 1e-14.
  for (double f = 0.25; f <= 3.0; f += 0.0625) pressures.push_back(limit_pa * f);
  int below = 0, above = 0;
  double worst_stretch = 0.0, worst_bulge = 0.0;
  for (double p : pressures) {
    const auto want = reference::chamberChain(p, po, paperChamber());
    const pf::WallSolution got = pf::solveWall(p, po, mu, kPaper.chamber_height_m[0], kPaper.chamber_gap_m[0],
                                               kPaper.wall_critical_height_m[0]);
    (p < limit_pa ? below : above) += 1;
    if (p == 0.0) {
      EXPECT_EQ(got.stretch_excess, 0.0);
      EXPECT_EQ(got.bulge_m, 0.0);
      continue;
    }
    worst_stretch = std::max(worst_stretch, absError(got.stretch_excess, want.stretch_excess) / want.stretch_excess);
    worst_bulge = std::max(worst_bulge, absError(got.bulge_m, want.bulge_m) / want.bulge_m);
  }
  EXPECT_GT(below, 100);
  EXPECT_GT(above, 100);
  // The series' own error is below 1.3e-18 (scripts/wall_series.py); what remains is rounding: s from P in four
  // roundings and a square root, then each sum's (the terms fall off by at least 7 times each): at most 4 ulp.
  EXPECT_LE(worst_stretch, 4 * 0x1p-52);
  EXPECT_LE(worst_bulge, 4 * 0x1p-52);
  RecordProperty("max_stretch_relative_error", pf_test::scientific(worst_stretch));
  RecordProperty("max_bulge_relative_error", pf_test::scientific(worst_bulge));
}

TEST(Stage4HalfAngle, MatchesReferenceForTheReferenceBulge) {
  // Feed the reference's own bulge so that only stage 4 is measured.
  const double b = kPaper.wall_critical_height_m[0], c = kPaper.chamber_gap_m[0];
  for (double p : kSweep) {
    const auto want = reference::chamberChain(p, kPaper.atmospheric_pressure_pa, paperChamber());
    const pf::HalfAngle got = pf::halfAngle(want.bulge_m, c, b);
    EXPECT_LE(absError(got.rad, want.half_angle_rad), 1e-15) << "P = " << p;
    EXPECT_LE(absError(got.cos, std::cos(want.half_angle_rad)), 1e-15);
    EXPECT_LE(absError(got.sin, std::sin(want.half_angle_rad)), 1e-15);
  }
}

TEST(Stage4HalfAngle, InvertsWangsRelationOverItsWholeRange) {
  // theta -> h(theta) -> theta round trip from 1e-12 rad to within 1e-6 rad of pi/2.
  const double b = 0.00575, c = 0.0005;
  for (double theta = 1e-12; theta < 1.5707963; theta = theta < 1e-3 ? theta * 3 : theta + 0.01) {
    const double h = pf::bulgeForHalfAngle(theta, c, b);
    EXPECT_LE(absError(pf::halfAngle(h, c, b).rad, theta), 1e-13 + 1e-15 * theta) << "theta = " << theta;
  }
}

TEST(Stage5JointAngles, AreSumsOfNeighbouringHalfAngles) {
  // Unequal chambers so that q_n = theta_{n-1} + theta_n is visible chamber by chamber.
  pf::RawParameterMap raw;
  raw["chamber_count"] = {{4}, false};
  raw["chamber_gap_m"] = {{0.0, 2e-5, 5e-5, 1e-4}, true};
  pf::FingerModel model(pf::FingerParameters::fromRaw(raw));
  pf::FingerWorkspace ws(model);
  const pf::FingerState& s = model.evaluate(150000, ws);
  // Joint 1: the base face's half angle theta_0 = s0 theta_1 (docs/MODEL.md stage 5) and chamber 1's.
  const double s0 = model.parameters().base_wall_share;
  ASSERT_GT(s0, 0.0);
  EXPECT_EQ(s.joint_angle_rad[0], s0 * s.half_angle_rad[0] + s.half_angle_rad[0]);
  for (int n = 1; n < 4; ++n) EXPECT_EQ(s.joint_angle_rad[n], s.half_angle_rad[n - 1] + s.half_angle_rad[n]);
  EXPECT_GT(s.half_angle_rad[0], s.half_angle_rad[3]);  // a smaller gap bends more
}

TEST(Stage6Backbone, WholeFingerMatchesReferenceOverDenseSweep) {
  pf::FingerModel model(kPaper);
  pf::FingerWorkspace ws(model);
  pf_test::FingerError worst;
  for (double p : kSweep) worst.merge(pf_test::fingerError(model.evaluate(p, ws), pf_test::referenceFinger(kPaper, p)));
  EXPECT_TRUE(worst.finite);
  EXPECT_LE(worst.half_angle_rad, pf_test::kAngleTolerance);
  EXPECT_LE(worst.joint_angle_rad, pf_test::kAngleTolerance);
  EXPECT_LE(worst.tip_angle_rad, pf_test::kAngleTolerance);
  EXPECT_LE(worst.point_m, pf_test::kPointTolerance);
  RecordProperty("max_half_angle_error_rad", pf_test::scientific(worst.half_angle_rad));
  RecordProperty("max_point_error_m", pf_test::scientific(worst.point_m));
}

TEST(Stage6Backbone, UnequalChambersMatchReference) {
  pf::RawParameterMap raw;
  raw["chamber_gap_m"] = {{0.0, 1e-5, 3e-5, 5.2e-5, 8e-5, 1.2e-4, 2e-4}, true};
  raw["segment_length_m"] = {{0.010, 0.011, 0.009, 0.010, 0.012, 0.008, 0.010}, true};
  raw["shear_modulus_pa"] = {{1e8, 2e8, 3e8, 2.2e8, 2.2e8, 5e8, 1e9}, true};
  const pf::FingerParameters params = pf::FingerParameters::fromRaw(raw);
  pf::FingerModel model(params);
  pf::FingerWorkspace ws(model);
  EXPECT_EQ(model.distinctChamberCount(), 7);
  pf_test::FingerError worst;
  for (double p : pf_test::pressureSweep(3e5, 60, 4)) {
    worst.merge(pf_test::fingerError(model.evaluate(p, ws), pf_test::referenceFinger(params, p)));
  }
  EXPECT_LE(worst.half_angle_rad, pf_test::kAngleTolerance);
  EXPECT_LE(worst.joint_angle_rad, pf_test::kAngleTolerance);
  EXPECT_LE(worst.point_m, pf_test::kPointTolerance);
}

// Joint 1 with a turning base face (docs/MODEL.md stage 5: theta_0 = s0 theta_1), identical and unequal chambers,
// against the reference, which adds theta_0 to q_1 in quad precision.
TEST(Stage5Joints, BaseWallShareMatchesReference) {
  for (double share : {0.28, 1.0}) {
    for (bool unequal : {false, true}) {
      pf::RawParameterMap raw;
      raw["base_wall_share"] = {{share}, false};
      if (unequal) raw["chamber_gap_m"] = {{3e-5, 1e-5, 3e-5, 5.2e-5, 8e-5, 1.2e-4, 2e-4}, true};
      const pf::FingerParameters params = pf::FingerParameters::fromRaw(raw);
      pf::FingerModel model(params);
      pf::FingerWorkspace ws(model);
      pf_test::FingerError worst;
      double ratio = 0.0;
      for (double p : pf_test::pressureSweep(3e5, 60, 4)) {
        const pf::FingerState& s = model.evaluate(p, ws);
        worst.merge(pf_test::fingerError(s, pf_test::referenceFinger(params, p)));
        if (!unequal && s.half_angle_rad[0] > 0) ratio = s.joint_angle_rad[0] / s.half_angle_rad[0];
      }
      SCOPED_TRACE("s0 = " + std::to_string(share) + (unequal ? ", unequal chambers" : ", identical chambers"));
      EXPECT_LE(worst.half_angle_rad, pf_test::kAngleTolerance);
      EXPECT_LE(worst.joint_angle_rad, pf_test::kAngleTolerance);
      EXPECT_LE(worst.tip_angle_rad, pf_test::kAngleTolerance);
      EXPECT_LE(worst.point_m, pf_test::kPointTolerance);
      if (!unequal) {
        EXPECT_NEAR(ratio, 1.0 + share, 1e-15);
      }
      // The thread-safe forms agree with the state.
      const double p = 1.5e5;
      const pf::FingerState& s = model.evaluate(p, ws);
      std::vector<double> q(static_cast<std::size_t>(params.chamber_count));
      ASSERT_TRUE(model.jointAnglesAt(p, q.data()));
      for (int i = 0; i < params.chamber_count; ++i) EXPECT_EQ(q[static_cast<std::size_t>(i)], s.joint_angle_rad[i]);
      EXPECT_NEAR(model.tipAngleAt(p), s.tip_angle_rad, 1e-15);
      // The inverse: the pressure for the tip angle reached at p gives p back.
      double gauge = 0.0;
      std::string why;
      ASSERT_TRUE(model.gaugeForTipAngle(s.tip_angle_rad, 1e6, gauge, why)) << why;
      EXPECT_NEAR(gauge, p, 1e-9 * p);
    }
  }
}
