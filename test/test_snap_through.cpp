// The snap-through under pressure control (docs/MODEL.md, "The snap-through"): a Gent wall jumps at its limit
// pressure to its far branch and falls back at that branch's lower turning point; the state depends on the path. The
// turning points and the far branch against the quad-precision reference (test/reference_quad.cpp: the law written
// literally, rounded once), evaluate() against the batch bit for bit, and the Neo-Hookean wall that has no far branch.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/membrane_wall.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "reference_quad.hpp"
#include "test_support.hpp"

namespace pf = pneumatic_finger;

namespace {

// The silicone wall of test_membrane_wall.cpp (mu = 20 kPa, t = 2 mm, L = 11.5 mm) with a late lock, J_m = 50: a
// limit point, then a minimum, then the lock.
constexpr double kMu = 2e4, kThickness = 0.002, kHeight = 0.0115, kJm = 50.0;

using pf_test::membraneFinger;

double referenceGauge(double delta) { return reference::membraneGaugePa({kMu, kThickness, kHeight, kJm}, delta); }

}  // namespace

TEST(SnapThrough, TheTurningPointsMatchTheQuadReference) {
  const pf::MembraneWall w = pf::membraneWall(kMu, kThickness, kHeight, kJm);
  ASSERT_TRUE(std::isfinite(w.limit_gauge_pa));
  ASSERT_TRUE(std::isfinite(w.far_turning_gauge_pa));
  EXPECT_GT(w.far_turning_stretch_excess, w.limit_stretch_excess);
  EXPECT_LT(w.far_turning_stretch_excess, w.locking_stretch_excess);
  EXPECT_LT(w.far_turning_gauge_pa, w.limit_gauge_pa);
  // A minimum of the reference's law: its value is well conditioned (flat), its place is not, so the value is compared
  // to 1e-12 and the place by the law rising on both sides.
  const double d = w.far_turning_stretch_excess;
  EXPECT_LT(std::fabs(w.far_turning_gauge_pa - referenceGauge(d)) / referenceGauge(d), 1e-12);
  double a = w.limit_stretch_excess, b = 0.999 * w.locking_stretch_excess;
  for (int i = 0; i < 300; ++i) {  // golden-section search for the reference's minimum
    const double x1 = b - 0.618 * (b - a), x2 = a + 0.618 * (b - a);
    (referenceGauge(x1) < referenceGauge(x2) ? b : a) = (x1 + x2) / 2;
  }
  const double reference_minimum = referenceGauge(0.5 * (a + b));
  EXPECT_LT(std::fabs(w.far_turning_gauge_pa - reference_minimum) / reference_minimum, 1e-12);
  EXPECT_GT(referenceGauge(d * (1 - 1e-3)), w.far_turning_gauge_pa);
  EXPECT_GT(referenceGauge(d * (1 + 1e-3)), w.far_turning_gauge_pa);
  // The limit pressure too, as test_membrane_wall checks its place.
  const double limit = reference::membraneLimitGaugePa({kMu, kThickness, kHeight, kJm});
  EXPECT_LT(std::fabs(w.limit_gauge_pa - limit) / limit, 1e-12);
}

TEST(SnapThrough, TheFarBranchSolvesTheLawToAnUlpOfBackwardError) {
  const pf::MembraneWall w = pf::membraneWall(kMu, kThickness, kHeight, kJm);
  int checked = 0;
  for (double p = w.far_turning_gauge_pa * (1 + 1e-9); p < 20 * w.limit_gauge_pa; p *= 1.05) {
    const double d = pf::membraneFarStretchExcess(w, p);
    ASSERT_TRUE(std::isfinite(d)) << p;
    EXPECT_GT(d, w.far_turning_stretch_excess);
    EXPECT_LT(d, w.locking_stretch_excess);
    EXPECT_LT(std::fabs(referenceGauge(d) - p) / p, 1e-12) << p;
    ++checked;
  }
  EXPECT_GT(checked, 50);
  EXPECT_TRUE(std::isnan(pf::membraneFarStretchExcess(w, w.far_turning_gauge_pa)));
  EXPECT_TRUE(std::isnan(pf::membraneFarStretchExcess(w, 0.5 * w.far_turning_gauge_pa)));
  const pf::MembraneWall neo = pf::membraneWall(kMu, kThickness, kHeight, 0.0);
  EXPECT_EQ(neo.far_turning_gauge_pa, std::numeric_limits<double>::infinity()) << "a Neo-Hookean wall has none";
  EXPECT_TRUE(std::isnan(pf::membraneFarStretchExcess(neo, 2 * neo.limit_gauge_pa)));
}

// A ramp up through the limit and down again: the jump at the limit pressure, the far branch held down to its
// turning point, the jump back, and between the two a hysteresis loop: two shapes at one pressure.
TEST(SnapThrough, ARampUpAndDownJumpsTwiceWithAHysteresisLoop) {
  const pf::FingerModel model(membraneFinger(kJm));
  pf::FingerWorkspace ws(model), fresh(model);
  const double limit = model.limitGaugePa(), turning = model.farTurningGaugePa();
  ASSERT_LT(turning, limit);
  const double below = std::nextafter(limit, 0.0);
  const double near_tip = model.evaluate(below, ws).tip_angle_rad;
  EXPECT_EQ(ws.state().status, pf::EvaluationStatus::kOk);
  const pf::FingerState& jumped = model.evaluate(limit, ws);
  EXPECT_EQ(jumped.status, pf::EvaluationStatus::kSnappedThrough);
  EXPECT_TRUE(ws.onFarBranch(0));
  EXPECT_GT(jumped.tip_angle_rad, near_tip + 0.5) << "the jump at the limit pressure bends the finger at once";
  const pf::MembraneWall w = pf::membraneWall(kMu, kThickness, kHeight, kJm);
  EXPECT_EQ(jumped.bulge_m[0], 0.5 * kHeight * pf::membraneFarStretchExcess(w, limit));
  // Down again: at a pressure of the loop the far shape, where the way up had the near one.
  const double middle = 0.5 * (turning + limit);
  const double far_tip = model.evaluate(middle, ws).tip_angle_rad;
  EXPECT_EQ(ws.state().status, pf::EvaluationStatus::kSnappedThrough);
  const double up_tip = model.evaluate(middle, fresh).tip_angle_rad;
  EXPECT_EQ(fresh.state().status, pf::EvaluationStatus::kOk);
  EXPECT_GT(far_tip, up_tip + 0.5) << "two shapes at one pressure";
  // Held down to the turning point (just above it: far), then back on the near branch, bit for bit a fresh ramp's.
  EXPECT_EQ(model.evaluate(std::nextafter(turning, limit), ws).status, pf::EvaluationStatus::kSnappedThrough);
  const pf::FingerState& back = model.evaluate(turning, ws);
  EXPECT_EQ(back.status, pf::EvaluationStatus::kOk);
  EXPECT_FALSE(ws.snappedThrough());
  EXPECT_EQ(back.tip_angle_rad, model.evaluate(turning, fresh).tip_angle_rad);
}

TEST(SnapThrough, ASingleEvaluationStartsFromTheBranchItIsGiven) {
  const pf::FingerModel model(membraneFinger(kJm));
  pf::FingerWorkspace ws(model);
  const double middle = 0.5 * (model.farTurningGaugePa() + model.limitGaugePa());
  const double near_tip = model.evaluate(middle, ws).tip_angle_rad;
  model.startBranch(ws, true);
  const pf::FingerState& far = model.evaluate(middle, ws);
  EXPECT_EQ(far.status, pf::EvaluationStatus::kSnappedThrough);
  EXPECT_GT(far.tip_angle_rad, near_tip);
  model.startBranch(ws, false);
  EXPECT_EQ(model.evaluate(middle, ws).tip_angle_rad, near_tip);
  // Below the turning point a far start falls back at once.
  model.startBranch(ws, true);
  EXPECT_EQ(model.evaluate(0.5 * model.farTurningGaugePa(), ws).status, pf::EvaluationStatus::kOk);
}

TEST(SnapThrough, TheBatchFollowsTheBranchesInOrderBitForBit) {
  const pf::FingerModel model(membraneFinger(kJm));
  const double limit = model.limitGaugePa(), turning = model.farTurningGaugePa();
  std::vector<double> ramp;
  for (int i = 0; i <= 40; ++i) ramp.push_back(1.5 * limit * i / 40);
  for (int i = 40; i >= 0; --i) ramp.push_back(1.5 * limit * i / 40);
  ramp.push_back(std::numeric_limits<double>::quiet_NaN());
  ramp.push_back(-100.0);
  pf::BatchBuffers buffers(ramp.size(), model.chamberCount());
  pf::FingerWorkspace batch_ws(model), ws(model);
  model.evaluateMany(ramp.data(), ramp.size(), buffers.outputs(), batch_ws);
  int snapped = 0;
  for (std::size_t i = 0; i + 2 < ramp.size(); ++i) {
    const pf::FingerState& s = model.evaluate(ramp[i], ws);
    EXPECT_EQ(buffers.status[i], static_cast<std::uint8_t>(s.status)) << i;
    EXPECT_EQ(buffers.tip_angle_rad[i], s.tip_angle_rad) << i;
    EXPECT_EQ(buffers.joint_angle_rad[i * 7 + 3], s.joint_angle_rad[3]) << i;
    snapped += s.status == pf::EvaluationStatus::kSnappedThrough;
    const bool far = ramp[i] >= limit || (i > 40 && ramp[i] > turning);
    EXPECT_EQ(s.status == pf::EvaluationStatus::kSnappedThrough, far) << ramp[i];
  }
  EXPECT_GT(snapped, 20);
  EXPECT_EQ(buffers.status[ramp.size() - 2], static_cast<std::uint8_t>(pf::EvaluationStatus::kNotFinite));
  EXPECT_EQ(buffers.status[ramp.size() - 1], static_cast<std::uint8_t>(pf::EvaluationStatus::kVacuum));
  EXPECT_FALSE(batch_ws.snappedThrough()) << "the sequence ended at rest, on the near branch";
}

TEST(SnapThrough, ANeoHookeanWallHasNoFarBranchAndStaysBeyondTheLimit) {
  const pf::FingerModel model(membraneFinger(0.0));
  EXPECT_EQ(model.farTurningGaugePa(), std::numeric_limits<double>::infinity());
  pf::FingerWorkspace ws(model);
  const double tip = model.evaluate(0.9 * model.limitGaugePa(), ws).tip_angle_rad;
  EXPECT_EQ(model.evaluate(1.1 * model.limitGaugePa(), ws).status, pf::EvaluationStatus::kBeyondLimitPoint);
  EXPECT_EQ(ws.state().tip_angle_rad, tip) << "the last shape stays";
  model.startBranch(ws, true);
  EXPECT_FALSE(ws.snappedThrough()) << "no far branch to start from";
}

TEST(SnapThrough, UnequalChambersSnapOneGroupAtATime) {
  // Chamber 7 stiffer: its limit pressure is higher, so the other six snap first.
  const pf::FingerModel model(membraneFinger(kJm, "shear_modulus_pa: [2e4, 2e4, 2e4, 2e4, 2e4, 2e4, 2.2e4]\n"));
  ASSERT_EQ(model.distinctChamberCount(), 2);
  pf::FingerWorkspace ws(model);
  const pf::FingerState& s = model.evaluate(model.limitGaugePa(), ws);
  EXPECT_EQ(s.status, pf::EvaluationStatus::kSnappedThrough);
  EXPECT_TRUE(ws.onFarBranch(0));
  EXPECT_FALSE(ws.onFarBranch(1));
  EXPECT_GT(s.half_angle_rad[0], s.half_angle_rad[6]);
}

// The inverse past the near branch: a tip angle of the far branch is the far branch's pressure, with the way there
// in the message; one between the branches is refused.
TEST(SnapThrough, TheInverseReachesTheFarBranchBySnapping) {
  const pf::FingerModel model(membraneFinger(kJm));
  pf::FingerWorkspace ws(model);
  model.startBranch(ws, true);
  for (double share : {0.9, 1.2, 3.0}) {
    const double p = share * model.limitGaugePa();
    const double tip = model.evaluate(p, ws).tip_angle_rad;
    ASSERT_EQ(ws.state().status, pf::EvaluationStatus::kSnappedThrough);
    double gauge = 0.0;
    std::string message;
    ASSERT_TRUE(model.gaugeForTipAngle(tip, 1e6, gauge, message)) << message;
    EXPECT_LT(std::fabs(gauge - p) / p, 1e-12) << share;
    EXPECT_NE(message.find("far branch: raise the pressure to at least"), std::string::npos) << message;
  }
  // Just past the near branch's largest angle: between the branches.
  double gauge = 0.0;
  std::string message;
  EXPECT_FALSE(model.gaugeForTipAngle(model.tipAngleBelowLimit() * 1.001, 1e6, gauge, message));
  EXPECT_NE(message.find("between the walls' branches"), std::string::npos) << message;
  // A far target beyond the allowed range is refused with the numbers.
  EXPECT_FALSE(model.gaugeForTipAngle(model.evaluate(3.0 * model.limitGaugePa(), ws).tip_angle_rad,
                                      2.0 * model.limitGaugePa(), gauge, message));
  EXPECT_NE(message.find("needs more than the allowed"), std::string::npos) << message;
}
