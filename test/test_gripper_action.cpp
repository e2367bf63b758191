// rostest: the gripper action (test/gripper_action.test). It succeeds at the goal's free pressure, stalls on an
// object at the pressure of the touch plus the squeeze margin (the touch computed here with the core's
// ContactSolver on the object's section), grasps with a grip force in newtons (max_effort) at the core's pressure for
// it, reports the grip force it reached, and aborts goals no pressure in range reaches (an angle, a force).
#include <actionlib/client/simple_action_client.h>
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <cmath>

#include "pneumatic_finger/GraspObject.h"
#include "pneumatic_finger/GripperCommandAction.h"
#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "grasp_object_support.hpp"
#include "ros_test_support.hpp"

namespace pf = pneumatic_finger;
using State = actionlib::SimpleClientGoalState;

namespace {

constexpr double kSqueezeMarginPa = 9806.65;  // the server's default
constexpr double kSettleTolerancePa = 200.0;  // the server's default

pf::FingerModel model() {
  std::string config;
  ros::NodeHandle("~").getParam("config", config);
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(config, raw);
  return pf::FingerModel(pf::FingerParameters::fromRaw(raw));
}

State send(actionlib::SimpleActionClient<pf::GripperCommandAction>& client, double position, double max_effort = 0) {
  pf::GripperCommandGoal goal;
  goal.position = position;
  goal.max_effort = max_effort;
  return client.sendGoalAndWait(goal, ros::Duration(20.0));
}

}  // namespace

TEST(GripperAction, ClosesStallsOnTheObjectAndAbortsWhatNoPressureReaches) {
  ros::NodeHandle nh;
  actionlib::SimpleActionClient<pf::GripperCommandAction> client("/gripper/gripper_action", true);
  ASSERT_TRUE(client.waitForServer(ros::Duration(30)));
  const pf::FingerModel finger = model();

  // Free: 0.5 rad at the inverse model's pressure.
  double free_pa = 0;
  std::string why;
  ASSERT_TRUE(finger.gaugeForTipAngle(0.5, 294199.5, free_pa, why)) << why;
  ASSERT_EQ(send(client, 0.5), State::SUCCEEDED);
  auto r = client.getResult();
  EXPECT_TRUE(r->reached_goal);
  EXPECT_FALSE(r->stalled);
  EXPECT_NEAR(r->position, 0.5, 0.01);
  EXPECT_NEAR(r->gauge_pa, free_pa, kSettleTolerancePa);
  EXPECT_EQ(r->effort, 0.0) << "no object: no grip force";

  // Unreachable: refused at once, naming the reason.
  const State far = send(client, 30.0);
  EXPECT_EQ(far, State::ABORTED);
  EXPECT_NE(far.getText().find("no gauge pressure up to"), std::string::npos) << far.getText();

  // A sphere whose section by the finger's plane is a 12 mm disk at (60, 30) mm in the finger's frame.
  ASSERT_EQ(send(client, 0.0), State::SUCCEEDED);
  ros::Publisher pub = nh.advertise<pf::GraspObject>("/grasp_object", 1, true);
  pub.publish(pf_test::sphereObject("f_segment_0", "ball", 0.012, 0.06, 0.03));
  const pf::ContactState touch = pf::ContactSolver(finger).solve(294199.5, pf::Obstacle::disk(0.06, 0.03, 0.012));
  ASSERT_TRUE(std::isfinite(touch.first_touch_gauge_pa));
  ros::Duration(1.0).sleep();  // the node's object timer picks it up

  ASSERT_EQ(send(client, 3.0), State::SUCCEEDED) << client.getState().getText();
  r = client.getResult();
  EXPECT_TRUE(r->stalled);
  EXPECT_FALSE(r->reached_goal);
  EXPECT_NEAR(r->gauge_pa, touch.first_touch_gauge_pa + kSqueezeMarginPa, kSettleTolerancePa);
  // The grip force reached is the core's force at the pressure the finger reports.
  pf::ContactTracker tracker(finger, pf::Obstacle::disk(0.06, 0.03, 0.012));
  auto force_at = [&](double p) { return pf::totalContactForceN(finger, p, tracker.solve(p)); };
  EXPECT_GT(r->effort, 0.0);
  EXPECT_NEAR(r->effort, force_at(r->gauge_pa), 1e-6 * r->effort);

  // A grip force in newtons: half what the finger gives at the top of its range, at the core's pressure for it.
  const double most_n = force_at(294199.5), want_n = 0.5 * most_n;
  double want_pa = 0;
  ASSERT_TRUE(pf::gaugeForContactForce(finger, [&](double p) { return tracker.solve(p); }, want_n, 294199.5, want_pa,
                                       why)) << why;
  ASSERT_EQ(send(client, 0.0), State::SUCCEEDED);
  ASSERT_EQ(send(client, 3.0, want_n), State::SUCCEEDED) << client.getState().getText();
  r = client.getResult();
  EXPECT_TRUE(r->stalled);
  // Commanded the force's pressure plus the settle tolerance, the fill settles from below no weaker than asked.
  EXPECT_GE(r->gauge_pa, want_pa);
  EXPECT_LE(r->gauge_pa, want_pa + 2 * kSettleTolerancePa);
  EXPECT_NEAR(r->effort, force_at(r->gauge_pa), 1e-6 * r->effort);
  EXPECT_GE(r->effort, want_n * (1 - 1e-6)) << "the grip asked for";
  EXPECT_NEAR(r->effort, want_n, 0.01 * want_n) << "within the settling tolerance's share of the force";

  // More than the finger gives anywhere in its range: aborted before anything is commanded, with the most it gives.
  ASSERT_EQ(send(client, 0.0), State::SUCCEEDED);
  const State strong = send(client, 3.0, 2.0 * most_n);
  EXPECT_EQ(strong, State::ABORTED);
  EXPECT_NE(strong.getText().find("/f cannot grip with"), std::string::npos) << strong.getText();
  EXPECT_NE(strong.getText().find("presses with at most"), std::string::npos) << strong.getText();
}

int main(int argc, char** argv) { return pf_test::runRosTests(argc, argv, "gripper_action_test", 2); }
