// The pick-and-place cell's schedule, driven with synthetic times (no ROS, no sleeps), and its grasp rule.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "pneumatic_finger/cell/cell_schedule.hpp"
#include "pneumatic_finger/cell/grasp_hold.hpp"
#include "pneumatic_finger/core/smoothstep.hpp"

namespace pf = pneumatic_finger;

namespace {

pf::CellWaypoints waypoints() {
  return {{0, 0}, {1, 0}, {1, 1}, {2, 0}, {2, 1}};
}

}  // namespace

TEST(CellSchedule, PhasesFollowInOrderWithTheGripperAndTheObjectPlaces) {
  const pf::CellSchedule s(waypoints(), 10.0);
  // Each phase's start (cumulative fractions 0, .14, .24, .39, .49, .63, .73, .88, .94 of 10 s), sampled just inside.
  const struct {
    double t;
    pf::CellPhase phase;
    bool closed;
    pf::ObjectPlace object;
  } expected[] = {
      {0.01, pf::CellPhase::kApproach, false, pf::ObjectPlace::kOnPickTable},
      {1.41, pf::CellPhase::kDescendToPick, false, pf::ObjectPlace::kOnPickTable},
      {2.41, pf::CellPhase::kGrasp, true, pf::ObjectPlace::kOnPickTable},
      {3.91, pf::CellPhase::kLift, true, pf::ObjectPlace::kHeld},
      {4.91, pf::CellPhase::kMove, true, pf::ObjectPlace::kHeld},
      {6.31, pf::CellPhase::kDescendToPlace, true, pf::ObjectPlace::kHeld},
      {7.31, pf::CellPhase::kPlace, false, pf::ObjectPlace::kOnPlaceTable},
      {8.81, pf::CellPhase::kRetreat, false, pf::ObjectPlace::kOnPlaceTable},
      {9.41, pf::CellPhase::kReturn, false, pf::ObjectPlace::kOnPlaceTable},
  };
  for (const auto& e : expected) {
    const pf::CellStep step = s.at(e.t);
    EXPECT_EQ(step.phase, e.phase) << e.t;
    EXPECT_EQ(step.gripper_closed, e.closed) << e.t;
    EXPECT_EQ(step.object, e.object) << e.t;
    EXPECT_EQ(step.cycle, 0) << e.t;
  }
  EXPECT_EQ(s.at(10.01).phase, pf::CellPhase::kApproach);
  EXPECT_EQ(s.at(25.0).cycle, 2);
}

TEST(CellSchedule, MotionsStartAndEndAtTheWaypoints) {
  const pf::CellSchedule s(waypoints(), 10.0);
  EXPECT_EQ(s.at(0.0).arm, (pf::ArmJoints{0, 0}));           // home
  EXPECT_EQ(s.at(2.4 - 1e-9).phase, pf::CellPhase::kDescendToPick);
  const pf::ArmJoints near_pick = s.at(2.4 - 1e-9).arm;       // the end of the descent
  EXPECT_NEAR(near_pick[0], 1.0, 1e-9);
  EXPECT_NEAR(near_pick[1], 1.0, 1e-9);
  EXPECT_EQ(s.at(3.0).arm, (pf::ArmJoints{1, 1}));           // held at pick while grasping
  // The retreat rises straight to above_place; the return leaves from there.
  const pf::ArmJoints retreated = s.at(9.4 - 1e-9).arm;
  EXPECT_NEAR(retreated[0], 2.0, 1e-9);
  EXPECT_NEAR(retreated[1], 0.0, 1e-9);
  // Halfway through a motion the smoothstep is at half the way.
  const pf::ArmJoints mid = s.at(0.7).arm;
  EXPECT_NEAR(mid[0], 0.5, 1e-12);
}

TEST(CellSchedule, TheObjectIsHeldOnlyOnceTheGraspPhaseIsComplete) {
  const pf::CellSchedule s(waypoints(), 10.0);
  EXPECT_EQ(s.at(3.85).object, pf::ObjectPlace::kOnPickTable);  // still inflating
  EXPECT_EQ(s.at(3.95).object, pf::ObjectPlace::kHeld);
}

TEST(CellSchedule, BadSettingsAreRefused) {
  pf::CellWaypoints w = waypoints();
  w.place = {1, 2, 3};
  EXPECT_THROW(pf::CellSchedule(w, 10.0), std::invalid_argument);
  EXPECT_THROW(pf::CellSchedule(waypoints(), 1.0), std::invalid_argument);
  EXPECT_THROW(pf::CellSchedule(waypoints(), NAN), std::invalid_argument);
}

// Each phase lasts what at() shows: the span of times it reports the phase for (scanned in 1 ms steps).
TEST(CellSchedule, APhasesDurationIsTheSpanAtReportsIt) {
  const pf::CellSchedule s(waypoints(), 10.0);
  for (pf::CellPhase phase : {pf::CellPhase::kGrasp, pf::CellPhase::kLift, pf::CellPhase::kReturn}) {
    int ticks = 0;
    for (int k = 0; k < 10000; ++k) ticks += s.at(1e-3 * (k + 0.5)).phase == phase;
    EXPECT_NEAR(s.phaseDurationS(phase), 1e-3 * ticks, 1e-3) << pf::cellPhaseName(phase);
  }
  EXPECT_DOUBLE_EQ(s.phaseDurationS(pf::CellPhase::kLift), 1.0);  // 10 % of the 10 s cycle
}

// The smoothstep's largest acceleration, against its second difference at the start (the peak), and the lift's
// inertia in the grasp rule: friction must hold margin x m (g + a).
TEST(GraspHold, TheLiftsInertiaAddsToTheWeight) {
  const double d = 0.1, T = 0.4, h = 1e-4;
  const double second_difference = (pf::smoothstep(2 * h / T) - 2 * pf::smoothstep(h / T) + pf::smoothstep(0)) * d /
                                   (h * h);
  EXPECT_NEAR(pf::smoothstepPeakAcceleration(d, T), second_difference, 1e-3 * second_difference);
  EXPECT_DOUBLE_EQ(pf::smoothstepPeakAcceleration(d, T), 3.75);
  // 3 fingers x 0.1 N, friction 1: 0.3 N. A 20 g part needs 1.5 x 0.02 x 9.80665 = 0.294 N at rest: held; lifted at
  // 1 m/s^2 it needs 1.5 x 0.02 x 10.80665 = 0.324 N: not.
  const pf::HoldVerdict still = pf::judgeHold(3, 0.1, 0.02, 1.0, 1.5);
  const pf::HoldVerdict lifted = pf::judgeHold(3, 0.1, 0.02, 1.0, 1.5, 1.0);
  EXPECT_TRUE(still.holds);
  EXPECT_FALSE(lifted.holds);
  EXPECT_DOUBLE_EQ(lifted.needed_n, 1.5 * 0.02 * (9.80665 + 1.0));
  EXPECT_NE(lifted.message.find("is less than 1.5 x its weight 0.196 N (0.02 kg) and its inertia lifted at 1 m/s^2"),
            std::string::npos) << lifted.message;
  EXPECT_EQ(still.message.find("inertia"), std::string::npos) << still.message;
}

// The grip the cell asks for is judgeHold's rule solved for the finger force: at it the grip holds, a hair under it,
// not. Where the gripper's most falls short, the limits are the part judgeHold holds at that most (this lift) and the
// cycle whose own schedule lifts gently enough (its lift phase rebuilt, not scaled).
TEST(GraspHold, TheGripAskedIsTheOneThePartAndTheLiftNeed) {
  const double needed = pf::requiredFingerForceN(3, 0.02, 1.0, 1.5, 1.0);
  EXPECT_NEAR(needed, 1.5 * 0.02 * 10.80665 / 3.0, 1e-15);
  EXPECT_TRUE(pf::judgeHold(3, needed * (1 + 1e-12), 0.02, 1.0, 1.5, 1.0).holds);
  EXPECT_FALSE(pf::judgeHold(3, needed * (1 - 1e-9), 0.02, 1.0, 1.5, 1.0).holds);

  const double rise_m = 0.1, cycle_s = 4.0;
  auto lift_at = [&](double cycle) {
    const pf::CellSchedule s(waypoints(), cycle);
    return pf::smoothstepPeakAcceleration(rise_m, s.phaseDurationS(pf::CellPhase::kLift));
  };
  const double most_n = 0.06;
  const pf::GripLimits short_of = pf::gripLimits(3, most_n, 0.01, 1.0, 1.5, lift_at(cycle_s), cycle_s);
  EXPECT_FALSE(short_of.enough);
  EXPECT_TRUE(pf::judgeHold(3, most_n, short_of.heaviest_part_kg * (1 - 1e-9), 1.0, 1.5, lift_at(cycle_s)).holds);
  EXPECT_FALSE(pf::judgeHold(3, most_n, short_of.heaviest_part_kg * (1 + 1e-9), 1.0, 1.5, lift_at(cycle_s)).holds);
  ASSERT_GT(short_of.shortest_cycle_s, cycle_s);
  const double slowest_lift = lift_at(short_of.shortest_cycle_s);
  EXPECT_NEAR(pf::requiredFingerForceN(3, 0.01, 1.0, 1.5, slowest_lift), most_n, 1e-12);
  EXPECT_NE(short_of.message.find("a cycle of at least"), std::string::npos) << short_of.message;
  EXPECT_TRUE(pf::gripLimits(3, 0.1, 0.01, 1.0, 1.5, lift_at(cycle_s), cycle_s).enough);
  // Too heavy even at rest: no cycle.
  const pf::GripLimits never = pf::gripLimits(3, 0.01, 0.01, 1.0, 1.5, lift_at(cycle_s), cycle_s);
  EXPECT_TRUE(std::isinf(never.shortest_cycle_s));
  EXPECT_NE(never.message.find("no cycle: even a slow lift"), std::string::npos) << never.message;
}
