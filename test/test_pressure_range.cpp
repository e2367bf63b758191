// The model's pressure range: one rule and one set of words, which finger_node's input policy, finger_model and
// Python all take from the core (pressure_range.hpp). Before, the node clamped, the CLI printed any pressure
// silently, and Python answered 15 rad at 4.9 MPa with status "ok".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "pneumatic_finger/core/evaluation_report.hpp"
#include "pneumatic_finger/core/pressure_input.hpp"
#include "pneumatic_finger/core/pressure_range.hpp"

namespace pf = pneumatic_finger;

TEST(PressureRange, ClampsAboveTheModelsRangeAndFlagsAboveTheValidated) {
  const pf::PressureRange range;  // 3 and 2 kg/cm2
  const pf::RangeCheck in = pf::checkGaugeRange(1e5, range);
  EXPECT_EQ(in.gauge_pa, 1e5);
  EXPECT_FALSE(in.clamped || in.above_validated);
  const pf::RangeCheck extrapolated = pf::checkGaugeRange(2.5e5, range);
  EXPECT_EQ(extrapolated.gauge_pa, 2.5e5);
  EXPECT_TRUE(extrapolated.above_validated && !extrapolated.clamped);
  const pf::RangeCheck clamped = pf::checkGaugeRange(4.9e6, range);
  EXPECT_EQ(clamped.gauge_pa, 294199.5);
  EXPECT_TRUE(clamped.clamped && clamped.above_validated);
  // At the top itself: in range. Not finite: left to the model, which refuses it with its own status.
  EXPECT_FALSE(pf::checkGaugeRange(294199.5, range).clamped);
  EXPECT_FALSE(pf::checkGaugeRange(INFINITY, range).clamped);
  EXPECT_TRUE(std::isnan(pf::checkGaugeRange(NAN, range).gauge_pa));
}

// A pressure the node's input policy already checked gives checkGaugeRange's answer: the same flags at every pressure
// of the range and beyond it (a clamped one evaluated at the top).
TEST(PressureRange, ACheckedInputIsCheckedByTheSameRule) {
  const pf::PressureRange range;
  for (double p : {-5e4, 0.0, 1e5, 196133.0, 2.5e5, 294199.5, 4.9e6}) {
    const pf::RangeCheck rule = pf::checkGaugeRange(p, range);
    const pf::RangeCheck input = pf::checkedInput(rule.gauge_pa, rule.clamped, range.validated_max_gauge_pa);
    EXPECT_EQ(input.gauge_pa, rule.gauge_pa) << p;
    EXPECT_EQ(input.clamped, rule.clamped) << p;
    EXPECT_EQ(input.above_validated, rule.above_validated) << p;
  }
}

TEST(PressureRange, TheWordsNameThePressureAndTheRangeInThePersonsDigits) {
  const pf::PressureRange range;
  EXPECT_EQ(pf::clampedMessage(4.9e6, range),
            "gauge pressure 4900000 Pa is above max_gauge_pa 294199.5 Pa, the top of the model's range: clamped to it");
  EXPECT_EQ(pf::vacuumMessage(-5), "gauge pressure -5 Pa is a vacuum, outside the model: the straight finger");
  EXPECT_EQ(pf::aboveValidatedMessage(91503.635757, {1e6, 9e4}),
            "gauge pressure 91503.6 Pa is above the validated range (0 to 90000 Pa): the twin extrapolates");
}

TEST(PressureRange, TheNodesInputPolicySaysTheSameWords) {
  pf::PressureInputSettings settings;
  pf::PressureInputPolicy policy(settings);
  const double absolute = settings.atmospheric_pa + 4.9e6;
  const pf::InputDecision d = policy.onMessage(absolute, 1.0, 1.0);
  EXPECT_TRUE(d.clamped);
  EXPECT_EQ(d.gauge_pa, 294199.5);
  EXPECT_EQ(d.problem, pf::clampedMessage(absolute - settings.atmospheric_pa, policy.range()));
  EXPECT_EQ(policy.report(1.1).message, d.problem);
  // Between the validated range and the model's: flagged, not clamped; both counted.
  const pf::InputDecision between = policy.onMessage(settings.atmospheric_pa + 2.5e5, 1.2, 1.2);
  EXPECT_FALSE(between.clamped);
  EXPECT_TRUE(between.out_of_range);
  EXPECT_EQ(between.gauge_pa, 2.5e5);
  EXPECT_EQ(policy.counters().clamped, 1);
  EXPECT_EQ(policy.counters().out_of_range, 2);
}

TEST(PressureRange, ABatchIsClampedAndMarkedRowByRow) {
  const pf::PressureRange range;
  const std::vector<double> in = {1e5, 4.9e6, -5, NAN, 1e9};
  std::vector<double> out(in.size());
  EXPECT_EQ(pf::clampToRange(in.data(), out.data(), in.size(), range), 2u);
  EXPECT_EQ(out[1], range.max_gauge_pa);
  EXPECT_EQ(out[4], range.max_gauge_pa);
  EXPECT_EQ(out[2], -5);
  EXPECT_STREQ(pf::evaluationStatusName(pf::EvaluationStatus::kClamped), "clamped to max_gauge_pa");
}

// The one report of every interface, case by case, written out by hand: the status keeps its old precedence (a
// refusal, then meets itself, then clamped, then the model's own) and the flags keep what the status hides. Before,
// a clamped pressure whose shape met itself reported "meets itself" alone in Python, the node and finger_model alike.
TEST(EvaluationReport, TheStatusKeepsItsPrecedenceAndTheFlagsKeepTheRest) {
  using S = pf::EvaluationStatus;
  struct Case {
    S model;
    bool clamped, above_validated, meets;
    S status;
    std::uint8_t flags;
  };
  const Case cases[] = {
      {S::kOk, false, false, false, S::kOk, 0},
      {S::kOk, false, true, false, S::kOk, pf::kFlagExtrapolated},
      {S::kOk, true, true, false, S::kClamped, pf::kFlagClamped | pf::kFlagExtrapolated},
      {S::kSnappedThrough, false, false, false, S::kSnappedThrough, pf::kFlagFarBranch},
      {S::kSnappedThrough, true, true, true, S::kMeetsItself,
       pf::kFlagClamped | pf::kFlagFarBranch | pf::kFlagMeetsItself | pf::kFlagExtrapolated},
      {S::kOk, false, false, true, S::kMeetsItself, pf::kFlagMeetsItself},
      {S::kVacuum, false, false, false, S::kVacuum, 0},
      {S::kBeyondLimitPoint, true, true, false, S::kBeyondLimitPoint, pf::kFlagClamped | pf::kFlagExtrapolated},
      {S::kSolverFailure, false, false, false, S::kSolverFailure, 0},
      {S::kNotFinite, false, false, false, S::kNotFinite, 0},
  };
  for (const Case& c : cases) {
    pf::RangeCheck range;
    range.clamped = c.clamped;
    range.above_validated = c.above_validated;
    const pf::EvaluationReport r = pf::reportEvaluation(c.model, range, c.meets);
    EXPECT_EQ(r.status, c.status) << pf::evaluationStatusName(c.model);
    EXPECT_EQ(r.flags, c.flags) << pf::evaluationStatusName(c.model) << ": " << pf::statusFlagNames(r.flags);
  }
  EXPECT_EQ(pf::statusFlagNames(0), "none");
  EXPECT_EQ(pf::statusFlagNames(pf::kFlagClamped | pf::kFlagMeetsItself), "clamped, meets itself");
}
