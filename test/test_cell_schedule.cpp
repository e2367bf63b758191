// The pick-and-place cell's schedule, driven with synthetic times (no ROS, no sleeps).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "pneumatic_finger/cell/cell_schedule.hpp"

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
