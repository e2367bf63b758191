// rostest: the cell with a real object (pick_and_place_cell.launch physics:=mujoco). MuJoCo carries or drops the part
// (cell_physics), and cell/events says what physics did at each of 3 cycles beside what the static rule expected:
// test/pick_and_place_cell_physics.test carries the cell's 10 g part; test/pick_and_place_cell_physics_heavy.test
// loses a 200 g one. The part's mass is the sequencer's parameter, so one program checks both.
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <string>
#include <vector>

#include "cell_watch.hpp"
#include "ros_test_support.hpp"

namespace {

int count(const std::vector<std::string>& events, const std::string& what) {
  int n = 0;
  for (const std::string& e : events) n += e.find(what) != std::string::npos;
  return n;
}

}  // namespace

TEST(CellPhysics, ThreeCyclesOfThePartMovedByPhysicsWithTheRulesVerdictBeside) {
  ros::NodeHandle nh;
  pf_test::CellWatch watch(nh);
  double mass_kg = 0.0;
  ASSERT_TRUE(ros::param::get("/cell_sequencer/object_mass_kg", mass_kg));
  const bool light = mass_kg < 0.05;
  const std::string physics = light ? "physics: the grip carried 'cylinder'" : "physics: 'cylinder' slipped out";
  const std::string rule = light ? "the static rule expects the grip to carry" : "the static rule expects the grip to lose";
  const ros::Time deadline = ros::Time::now() + ros::Duration(100);
  std::vector<std::string> events;
  while (ros::Time::now() < deadline) {
    events = watch.snapshot().events;
    if (count(events, "physics: the grip carried") + count(events, "slipped out of the grip") >= 3) break;
    ros::Duration(0.1).sleep();
  }
  std::string all;
  for (const std::string& e : events) all += e + "\n";
  EXPECT_EQ(count(events, physics), 3) << all;
  EXPECT_EQ(count(events, rule), 3) << all;
  // Every lift is reported; the light part starts it in every finger's grip (the heavy one, sitting on the table
  // under the fingers' light squeeze, may have a finger that has just let go).
  EXPECT_EQ(count(events, "physics: the lift starts with "), 3) << all;
  if (light) {
    EXPECT_EQ(count(events, "physics: the lift starts with 3 of 3 fingers"), 3) << all;
  }
  EXPECT_EQ(count(events, "grasped 'cylinder'"), 0) << "the sequencer attached the part: " << all;
}

int main(int argc, char** argv) { return pf_test::runRosTests(argc, argv, "cell_physics_test", 2); }
