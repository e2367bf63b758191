// The gripper action's plan: which pressure a goal needs, with and without an object, and which goals it refuses.
#include <gtest/gtest.h>

#include <cmath>

#include "pneumatic_finger/core/grasp_plan.hpp"

namespace pf = pneumatic_finger;
using Kind = pf::GripperPlan::Kind;

TEST(GraspPlan, WithoutAnObjectTheSlowestFingerSetsThePressure) {
  const auto plan = pf::planGripperCommand({{"a", 1000, NAN}, {"b", 1500, NAN}, {"c", 1200, NAN}}, 0.5, 3e5, 1e4, false);
  EXPECT_EQ(plan.kind, Kind::kClose);
  EXPECT_EQ(plan.gauge_pa, 1500);
  EXPECT_NE(plan.message.find("b needs the most"), std::string::npos) << plan.message;
}

TEST(GraspPlan, AnObjectEveryFingerTouchesFirstIsGraspedAtTheLastTouchPlusTheMargin) {
  const auto plan = pf::planGripperCommand({{"a", 9e4, 5e4}, {"b", 9e4, 6e4}, {"c", NAN, 5.5e4}}, 2.0, 3e5, 1e4, true);
  EXPECT_EQ(plan.kind, Kind::kGrasp);
  EXPECT_EQ(plan.gauge_pa, 7e4);
  // The margin never passes the limit.
  EXPECT_EQ(pf::planGripperCommand({{"a", NAN, 2.95e5}}, 2.0, 3e5, 1e4, true).gauge_pa, 3e5);
}

TEST(GraspPlan, AGoalBeforeTheTouchClosesFreeAndSaysWhy) {
  const auto plan = pf::planGripperCommand({{"a", 2e4, 5e4}, {"b", 2e4, 6e4}}, 0.3, 3e5, 1e4, true);
  EXPECT_EQ(plan.kind, Kind::kClose);
  EXPECT_EQ(plan.gauge_pa, 2e4);
  EXPECT_NE(plan.message.find("before every finger touches"), std::string::npos) << plan.message;
  // One finger that never touches: no grasp, the goal alone decides.
  const auto missed = pf::planGripperCommand({{"a", 9e4, 5e4}, {"b", 9e4, NAN}}, 1.0, 3e5, 1e4, true);
  EXPECT_EQ(missed.kind, Kind::kClose);
  EXPECT_NE(missed.message.find("b does not touch"), std::string::npos) << missed.message;
}

TEST(GraspPlan, UnreachableGoalsAreRefusedNamingTheFingerAndTheLimit) {
  const auto plan = pf::planGripperCommand({{"a", 1e5, NAN}, {"b", NAN, NAN}}, 3.0, 3e5, 1e4, false);
  EXPECT_EQ(plan.kind, Kind::kUnreachable);
  EXPECT_NE(plan.message.find("b's tip to 3 rad"), std::string::npos) << plan.message;
  // The limit (max_effort) below what the goal needs.
  EXPECT_EQ(pf::planGripperCommand({{"a", 1e5, NAN}}, 1.0, 5e4, 1e4, false).kind, Kind::kUnreachable);
  // ... and below the object's touch.
  EXPECT_EQ(pf::planGripperCommand({{"a", NAN, 6e4}}, 3.0, 5e4, 1e4, true).kind, Kind::kUnreachable);
  EXPECT_EQ(pf::planGripperCommand({}, 1.0, 3e5, 1e4, false).kind, Kind::kUnreachable);
}

// The cell's release (goal 0 rad) was logged "close to 0 rad at 0 Pa (/finger_c needs the most); the goal comes
// before every finger touches the object": no finger needs anything to open.
TEST(GraspPlan, AReleaseSaysItOpens) {
  const auto plan =
      pf::planGripperCommand({{"/finger_a", 0, 5e4}, {"/finger_b", 0, 6e4}, {"/finger_c", 0, 7e4}}, 0.0, 3e5, 1e4, true);
  EXPECT_EQ(plan.kind, Kind::kClose);
  EXPECT_EQ(plan.gauge_pa, 0);
  EXPECT_EQ(plan.message, "open: vent to 0 Pa, where every finger is at the 0 rad goal");
}

// Numbers in the plan's words as a person reads them, not with 17 digits or the stream's six.
TEST(GraspPlan, NumbersReadAsWritten) {
  const auto plan = pf::planGripperCommand({{"a", 91503.635757, NAN}}, 0.1, 3e5, 1e4, false);
  EXPECT_EQ(plan.message, "close to 0.1 rad at 91503.6 Pa (a needs the most)");
}
