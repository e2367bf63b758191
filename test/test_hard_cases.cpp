// docs/MODEL.md, "Where the arithmetic is hard": one named test per case. The default (robust) solver must stay within
// 1e-12 rad / 1e-12 m of the quad reference; the paper solver's behaviour on the same inputs is recorded (where
// it fails, the assertion says how) so that a change in either shows up here.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/self_contact.hpp"
#include "pneumatic_finger/core/units.hpp"
#include "pneumatic_finger/core/stages.hpp"
#include "test_support.hpp"

namespace pf = pneumatic_finger;
using pf_test::absError;

namespace {

const pf::FingerParameters kPaper = pf::FingerParameters::defaults();

pf::FingerParameters withGap(double gap_m) {
  pf::RawParameterMap raw;
  raw["chamber_gap_m"] = {{gap_m}, false};
  return pf::FingerParameters::fromRaw(raw);
}

// Worst error of a whole-finger evaluation over @p pressures.
pf_test::FingerError worstOver(const pf::FingerParameters& params, pf::SolverKind solver,
                               const std::vector<double>& pressures) {
  pf::ModelOptions options;
  options.solver = solver;
  pf::FingerModel model(params, options);
  pf::FingerWorkspace ws(model);
  pf_test::FingerError worst;
  for (double p : pressures) worst.merge(pf_test::fingerError(model.evaluate(p, ws), pf_test::referenceFinger(params, p)));
  return worst;
}

void expectRobustExact(const pf_test::FingerError& e) {
  EXPECT_TRUE(e.finite);
  EXPECT_LE(e.half_angle_rad, pf_test::kAngleTolerance);
  EXPECT_LE(e.joint_angle_rad, pf_test::kAngleTolerance);
  EXPECT_LE(e.tip_angle_rad, pf_test::kAngleTolerance);
  EXPECT_LE(e.point_m, pf_test::kPointTolerance);
}


}  // namespace

// P -> 0: lambda - 1 ~ sqrt(g/3) has an infinite slope; computing lambda and then subtracting 1 loses digits.
TEST(HardCase, NearRestStretchExcessKeepsItsDigits) {
  const auto chamber = pf_test::chambersOf(kPaper)[0];
  for (double p = 1e-12; p <= 1e3; p *= 10) {
    const auto want = reference::chamberChain(p, kPaper.atmospheric_pressure_pa, chamber);
    const double robust = pf::stretchExcess(want.energy_group);
    EXPECT_LE(absError(robust, want.stretch_excess), 4e-16 * want.stretch_excess) << "P = " << p;
  }
  // Recorded: the paper's eq 10-12 form returns lambda, so lambda - 1 cancels; at 1e-6 Pa it keeps < 2 digits and
  // at 1e-9 Pa none (it returns lambda = 1 exactly, or a value off by 100 %).
  const double g6 = pf::energyGroup(1e-6, kPaper.atmospheric_pressure_pa, kPaper.shear_modulus_pa[0]);
  const double g9 = pf::energyGroup(1e-9, kPaper.atmospheric_pressure_pa, kPaper.shear_modulus_pa[0]);
  const double paper_rel_6 = std::fabs(pf::paper::stretch(g6) - 1 - pf::stretchExcess(g6)) / pf::stretchExcess(g6);
  const double paper_rel_9 = std::fabs(pf::paper::stretch(g9) - 1 - pf::stretchExcess(g9)) / pf::stretchExcess(g9);
  EXPECT_GT(paper_rel_6, 1e-3) << "the paper's stretch at 1e-6 Pa was expected to lose most digits";
  EXPECT_GT(paper_rel_9, 0.5) << "the paper's stretch at 1e-9 Pa was expected to lose all digits";
  RecordProperty("paper_stretch_excess_rel_error_at_1e-6_Pa", pf_test::scientific(paper_rel_6));
}

// Near rest, a^3 - 1 and sqrt(2 lambda^2 - 1) - 1 cancel; the factored forms do not.
TEST(HardCase, NearRestBulgeUsesFactoredForm) {
  const auto chamber = pf_test::chambersOf(kPaper)[0];
  double paper_worst = 0;
  for (double p = 1e-9; p <= 1e4; p *= 10) {
    const auto want = reference::chamberChain(p, kPaper.atmospheric_pressure_pa, chamber);
    const double robust = pf::bulge(pf::stretchExcess(want.energy_group), kPaper.chamber_height_m[0]);
    EXPECT_LE(absError(robust, want.bulge_m), 8e-16 * want.bulge_m) << "P = " << p;  // see Stage3Bulge
    const double paper = pf::paper::bulge(pf::paper::stretch(want.energy_group), kPaper.chamber_height_m[0]);
    paper_worst = std::max(paper_worst, absError(paper, want.bulge_m) / want.bulge_m);
  }
  EXPECT_GT(paper_worst, 0.5) << "recorded: the direct forms lose every digit of the bulge at 1e-9 Pa";
}

// h ~ c: theta crosses 0 and the quartic's constant term 16 h^2 (h^2 - c^2) vanishes.
TEST(HardCase, ContactCrossing) {
  const double pc = pf::contactGaugePa(kPaper.chamber_height_m[0], kPaper.chamber_gap_m[0],
                                       kPaper.shear_modulus_pa[0], kPaper.atmospheric_pressure_pa);
  std::vector<double> pressures;
  for (int k = 1; k <= 15; ++k) {
    pressures.push_back(pc * (1 - std::pow(10.0, -k)));
    pressures.push_back(pc * (1 + std::pow(10.0, -k)));
  }
  pressures.push_back(pc);
  expectRobustExact(worstOver(kPaper, pf::SolverKind::kRobust, pressures));
  pf::FingerModel model(kPaper);
  pf::FingerWorkspace ws(model);
  EXPECT_EQ(model.evaluate(pc * (1 - 1e-12), ws).half_angle_rad[0], 0.0);
  EXPECT_GT(model.evaluate(pc * (1 + 1e-12), ws).half_angle_rad[0], 0.0);
  // For the same (double) bulge, the robust solver keeps the relative accuracy of theta right down to the
  // crossing, where theta is 1e-17 rad: it forms h - c directly, exactly. Recorded: the paper's quartic keeps its
  // absolute error near 1e-16 rad but loses its relative accuracy (its constant term 16 h^2 (h^2 - c^2) cancels):
  // within 1e-14 above contact it is off by tens of percent.
  const double b = kPaper.wall_critical_height_m[0], c = kPaper.chamber_gap_m[0];
  const double h14 = c * (1 + 1e-14);
  const double want14 = reference::halfAngleForBulge(h14, c, b);
  ASSERT_GT(want14, 0.0);
  EXPECT_LE(absError(pf::halfAngle(h14, c, b).rad, want14), 1e-14 * want14);
  // The paper's form, within 1e-14 of contact (its error there depends on c's last bits: the worst of ten heights).
  double paper_rel = 0.0;
  for (int m = 1; m <= 10; ++m) {
    const double h = c * (1 + m * 1e-15), want = reference::halfAngleForBulge(h, c, b);
    if (want > 0.0) paper_rel = std::max(paper_rel, absError(pf::paper::halfAngle(h, c, b), want) / want);
  }
  EXPECT_GT(paper_rel, 0.1);
  RecordProperty("paper_half_angle_worst_relative_error_within_1e-14_of_contact", pf_test::scientific(paper_rel));
  for (int k = 1; k <= 15; ++k) {
    const double h = c * (1 + std::pow(10.0, -k));
    const double want = reference::halfAngleForBulge(h, c, b);
    EXPECT_LE(absError(pf::halfAngle(h, c, b).rad, want), 1e-14 * want) << "k = " << k;
    EXPECT_LE(absError(pf::paper::halfAngle(h, c, b), want), 1e-15) << "k = " << k;
  }
}

// Ferrari's resolvent discriminant: positive in exact arithmetic over the validated range, it tends to 0 as
// theta -> pi/2 (the quartic tends to (x^2 - 1)^2) and from about 1e8 Pa its sign is decided by rounding, so
// eq 33 switches branch back and forth: the paper's "point that lacks a derivative".
TEST(HardCase, ResolventBranchSwitch) {
  std::vector<double> pressures;
  for (double e = 7.5; e <= 9.0; e += 0.02) pressures.push_back(std::pow(10.0, e));
  expectRobustExact(worstOver(kPaper, pf::SolverKind::kRobust, pressures));
  // The branch really does switch in this band (else the test is not testing the hard case).
  const double b = kPaper.wall_critical_height_m[0], c = kPaper.chamber_gap_m[0];
  int switches = 0;
  bool prev_positive = true;
  for (double p : pressures) {
    const double h = pf::bulge(pf::stretchExcess(pf::energyGroup(p, kPaper.atmospheric_pressure_pa,
                                                                  kPaper.shear_modulus_pa[0])),
                               kPaper.chamber_height_m[0]);
    const bool positive = pf::paper::ferrariTerms(pf::paper::quarticCoefficients(h, c, b)).discriminant >= 0;
    switches += positive != prev_positive;
    prev_positive = positive;
  }
  EXPECT_GE(switches, 2);
  // Recorded: the paper solver misses 1e-12 rad here (4e-11 rad at 1e8 Pa).
  const auto chamber = pf_test::chambersOf(kPaper)[0];
  const auto want = reference::chamberChain(1e8, kPaper.atmospheric_pressure_pa, chamber);
  const double paper_at_1e8 = absError(pf::paper::halfAngle(want.bulge_m, c, b), want.half_angle_rad);
  EXPECT_GT(paper_at_1e8, 1e-12);
  RecordProperty("paper_half_angle_error_at_1e8_Pa", pf_test::scientific(paper_at_1e8));
}

// Large P: theta -> pi/2, where asin(y) is ill-conditioned (d theta/dy = 1/cos theta); and pressures so large
// that g overflows.
TEST(HardCase, LargePressureHalfAngleNearHalfPi) {
  const std::vector<double> pressures = {1e7, 1e8, 1e9, 1e10, 1e12, 1e15, 1e20, 1e50, 1e100, 1e200, 1e300, DBL_MAX};
  expectRobustExact(worstOver(kPaper, pf::SolverKind::kRobust, pressures));
  pf::FingerModel model(kPaper);
  pf::FingerWorkspace ws(model);
  EXPECT_EQ(model.evaluate(DBL_MAX, ws).half_angle_rad[0], M_PI_2);
  // Recorded: the paper solver has no root (NaN) from 1e9 Pa on, where theta > 1.5688 rad.
  const auto chamber = pf_test::chambersOf(kPaper)[0];
  const double b = kPaper.wall_critical_height_m[0], c = kPaper.chamber_gap_m[0];
  for (double p : {1e9, 1e10, 1e12}) {
    const auto want = reference::chamberChain(p, kPaper.atmospheric_pressure_pa, chamber);
    EXPECT_TRUE(std::isnan(pf::paper::halfAngle(want.bulge_m, c, b))) << "P = " << p;
  }
}

// c -> 0 or b >> c: the quartic becomes biquadratic (B = D = 0 at c = 0, so q = 0 and eq 34 divides 0 by alpha).
TEST(HardCase, NearlyBiquadraticQuartic) {
  const std::vector<double> pressures = pf_test::pressureSweep(3e5, 60, 5);
  for (double gap : {0.0, 1e-15, 1e-12, 1e-9}) {
    SCOPED_TRACE("chamber_gap_m = " + std::to_string(gap));
    expectRobustExact(worstOver(withGap(gap), pf::SolverKind::kRobust, pressures));
  }
  // At c = 0 eq 15 is h = (b/2) tan(theta): the robust solver returns atan(2h/b) to the last bit.
  const double h = 1e-3, b = 0.00575;
  EXPECT_DOUBLE_EQ(pf::halfAngle(h, 0.0, b).rad, std::atan(2 * h / b));
  // Recorded: the paper solver has no answer at c = 0 (q = 0 and alpha0 = 0 in eq 34), and misses 1e-12 rad at
  // c = 1e-15 m and 1e-9 m (4e-11 rad: near rest its bulge cancels, and with c tiny those bulges already bend).
  EXPECT_EQ(worstOver(withGap(0.0), pf::SolverKind::kPaper, pressures).half_angle_rad, INFINITY);
  for (double gap : {1e-15, 1e-9}) {
    const double paper = worstOver(withGap(gap), pf::SolverKind::kPaper, pressures).half_angle_rad;
    EXPECT_GT(paper, 1e-12) << "gap " << gap;
    RecordProperty("paper_half_angle_error_gap_" + std::to_string(gap), pf_test::scientific(paper));
  }
}

// Bad input: NaN and inf are refused and leave the last state; vacuum gives the rest shape; absurd pressures
// stay finite; non-physical geometry is refused with the key named.
TEST(HardCase, BadPressureInput) {
  pf::FingerModel model(kPaper);
  pf::FingerWorkspace ws(model);
  const pf::FingerState before = model.evaluate(150000, ws);
  for (double bad : {NAN, INFINITY, -INFINITY}) {
    const pf::FingerState& s = model.evaluate(bad, ws);
    EXPECT_EQ(s.status, pf::EvaluationStatus::kNotFinite);
    EXPECT_EQ(s.joint_angle_rad, before.joint_angle_rad);
    EXPECT_EQ(s.backbone_m, before.backbone_m);
  }
  const pf::FingerState& vacuum = model.evaluate(-50000, ws);
  EXPECT_EQ(vacuum.status, pf::EvaluationStatus::kVacuum);
  EXPECT_TRUE(vacuum.joint_angle_rad.isZero(0));
  EXPECT_EQ(vacuum.tip().y(), 0.0);
  for (double absurd : {1e12, -1e300, 5e-324, -5e-324}) {
    const pf::FingerState& s = model.evaluate(absurd, ws);
    EXPECT_TRUE(s.backbone_m.allFinite()) << absurd;
    EXPECT_TRUE(s.joint_angle_rad.allFinite()) << absurd;
  }
  EXPECT_EQ(model.evaluate(150000, ws).status, pf::EvaluationStatus::kOk);
}

TEST(HardCase, NonPhysicalGeometryIsRefusedNamingTheKey) {
  const std::vector<std::pair<std::string, double>> bad = {
      {"chamber_height_m", 0.0},   {"chamber_height_m", -0.01}, {"wall_critical_height_m", 0.02},
      {"wall_critical_height_m", 0.0}, {"chamber_gap_m", -1e-6}, {"chamber_count", 0},
      {"segment_length_m", 0.0},   {"base_segment_length_m", -0.015}};
  for (const auto& kv : bad) {
    pf::RawParameterMap raw;
    raw[kv.first] = {{kv.second}, false};
    try {
      pf::FingerParameters::fromRaw(raw);
      ADD_FAILURE() << kv.first << " = " << kv.second << " was accepted";
    } catch (const pf::ParameterError& e) {
      EXPECT_NE(std::string(e.what()).find(kv.first), std::string::npos) << e.what();
    }
  }
}

// Where the backbone meets itself. The reference is geometry drawn by hand: a square spiral that
// crosses its first side, a C that turns by 270 degrees without closing, a chain whose end lands on its base.
TEST(HardCase, TheBackboneMeetingItselfIsFoundAndOnlyThen) {
  const auto chain = [](std::vector<Eigen::Vector2d> points) {
    Eigen::Matrix2Xd m(2, static_cast<Eigen::Index>(points.size()));
    for (std::size_t i = 0; i < points.size(); ++i) m.col(static_cast<Eigen::Index>(i)) = points[i];
    return m;
  };
  const double quarter = pf::kPi / 2;
  // Out 2, up 1, back 1.5, down 2: the last side crosses the first (at x = 0.5).
  const Eigen::Matrix2Xd spiral = chain({{0, 0}, {2, 0}, {2, 1}, {0.5, 1}, {0.5, -1}});
  const double spiral_q[] = {quarter, quarter, quarter};
  EXPECT_TRUE(pf::backboneMeetsItself(spiral, spiral_q));
  // Out 2, up 1, back 1, down 0.5: three quarter turns, open.
  const Eigen::Matrix2Xd c_shape = chain({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 0.5}});
  EXPECT_FALSE(pf::backboneMeetsItself(c_shape, spiral_q));
  // Down exactly onto the first side: touching is meeting.
  const Eigen::Matrix2Xd touch = chain({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 0}});
  EXPECT_TRUE(pf::backboneMeetsItself(touch, spiral_q));
  // The model's own chain: the paper law at a tenth of its stiffness curls past a full turn between 200 and 290 kPa.
  pf::RawParameterMap raw;
  raw["shear_modulus_pa"] = {{2e7}, false};
  const pf::FingerParameters soft = pf::FingerParameters::fromRaw(raw);
  const pf::FingerModel model(soft);
  pf::FingerWorkspace ws(model);
  const pf::FingerState& open = model.evaluate(2e5, ws);
  EXPECT_FALSE(pf::backboneMeetsItself(open.backbone_m, open.joint_angle_rad.data()));
  EXPECT_FALSE(pf::jointsMeetThemselves(soft, open.joint_angle_rad.data()));
  const pf::FingerState& curled = model.evaluate(2.9e5, ws);
  EXPECT_GT(curled.tip_angle_rad, 2 * pf::kPi - 0.5);
  EXPECT_TRUE(pf::backboneMeetsItself(curled.backbone_m, curled.joint_angle_rad.data()));
  EXPECT_TRUE(pf::jointsMeetThemselves(soft, curled.joint_angle_rad.data())) << "built from the joints alone";
  EXPECT_EQ(pf::selfContactMessage(6.5), "the finger meets itself (tip angle 6.5 rad): its backbone crosses itself, "
                                         "where the model, which has no self-contact, passes through the finger");
}
