// GraspObjectTracker: the grasp object as one finger sees it, driven with poses of the test's own, without ROS. The
// reference for the contact answers is the core's ContactSolver on the section the test cuts itself; the statuses,
// the recut on a new pose only, and the counters are checked as finger_state and diagnostics show them.
#include <gtest/gtest.h>

#include <cmath>

#include "pneumatic_finger/core/grasp_object.hpp"
#include "pneumatic_finger/core/units.hpp"

namespace pf = pneumatic_finger;

namespace {

// A ball of radius r at (x, y, z) of its own frame, the frame at the origin of the finger's.
pf::SolidObject ball(double x, double y, double z, double r) {
  pf::SolidObject s;
  s.shape = pf::SolidObject::Shape::kSphere;
  s.radius_m = r;
  s.pose = Eigen::Translation3d(x, y, z) * Eigen::Isometry3d::Identity();
  return s;
}

class GraspObjectTest : public ::testing::Test {
 protected:
  const pf::FingerModel model_{pf::FingerParameters::defaults()};
  pf::GraspObjectTracker tracker_{model_, pf::kModelMaxGaugePa};
};

}  // namespace

TEST_F(GraspObjectTest, WithoutAnObjectTheFingerIsFreeAndNothingIsCut) {
  EXPECT_EQ(tracker_.status(), pf::GraspObjectStatus::kNone);
  EXPECT_FALSE(tracker_.inReach());
  EXPECT_FALSE(tracker_.locate(Eigen::Isometry3d::Identity()));  // nothing to locate
  EXPECT_TRUE(std::isnan(tracker_.touchGaugePa()));
  EXPECT_STREQ(pf::graspObjectStatusName(tracker_.status()), "none");
}

TEST_F(GraspObjectTest, ABallInReachGivesTheContactSolversAnswersAndItsFirstTouch) {
  const pf::SolidObject object = ball(0.06, 0.03, 0.001, 0.012);
  tracker_.setObject(object);
  ASSERT_TRUE(tracker_.locate(Eigen::Isometry3d::Identity()));
  EXPECT_EQ(tracker_.status(), pf::GraspObjectStatus::kClear);
  ASSERT_TRUE(tracker_.inReach());
  EXPECT_EQ(tracker_.sectionsCut(), 1);
  // The reference: the section cut here, and the contact rule from scratch on it.
  const auto section = pf::sectionByFingerPlane(object);
  ASSERT_TRUE(section.has_value());
  const pf::ContactSolver solver(model_);
  const pf::ContactState full = solver.solve(pf::kModelMaxGaugePa, *section);
  ASSERT_EQ(full.status, pf::ContactState::Status::kInContact);
  EXPECT_EQ(tracker_.touchGaugePa(), full.first_touch_gauge_pa);
  for (double p : {0.5 * full.first_touch_gauge_pa, full.first_touch_gauge_pa, 250000.0}) {
    const pf::ContactState got = tracker_.solve(p), want = solver.solve(p, *section);
    EXPECT_EQ(got.joint_angle_rad, want.joint_angle_rad) << "P = " << p;  // bit for bit
    EXPECT_EQ(got.backbone_m, want.backbone_m) << "P = " << p;
    EXPECT_EQ(tracker_.statusWith(got), want.status == pf::ContactState::Status::kInContact
                                            ? pf::GraspObjectStatus::kTouching
                                            : pf::GraspObjectStatus::kClear)
        << "P = " << p;
  }
  EXPECT_EQ(tracker_.statusWith(tracker_.solve(250000.0)), pf::GraspObjectStatus::kTouching);
}

TEST_F(GraspObjectTest, TheSameObjectInAnotherFrameIsTheSameSection) {
  // The ball given in a frame turned 30 degrees about z and shifted, located with that frame's pose.
  const Eigen::Isometry3d finger_from_frame =
      Eigen::Translation3d(0.01, -0.02, 0.0) * Eigen::AngleAxisd(0.5235987755982988, Eigen::Vector3d::UnitZ());
  const pf::SolidObject in_finger = ball(0.06, 0.03, 0.001, 0.012);
  pf::SolidObject in_frame = in_finger;
  in_frame.pose = finger_from_frame.inverse() * in_finger.pose;
  tracker_.setObject(in_frame);
  ASSERT_TRUE(tracker_.locate(finger_from_frame));
  pf::GraspObjectTracker direct(model_, pf::kModelMaxGaugePa);
  direct.setObject(in_finger);
  ASSERT_TRUE(direct.locate(Eigen::Isometry3d::Identity()));
  EXPECT_NEAR(tracker_.touchGaugePa(), direct.touchGaugePa(), 1e-6 * direct.touchGaugePa());
}

TEST_F(GraspObjectTest, AnUnchangedPoseKeepsTheSectionAndANewOneCutsAgain) {
  tracker_.setObject(ball(0.06, 0.03, 0.001, 0.012));
  ASSERT_TRUE(tracker_.locate(Eigen::Isometry3d::Identity()));
  EXPECT_FALSE(tracker_.locate(Eigen::Isometry3d::Identity()));  // a still arm and object: nothing to do
  EXPECT_EQ(tracker_.sectionsCut(), 1);
  EXPECT_TRUE(tracker_.locate(Eigen::Translation3d(0.0, 0.001, 0.0) * Eigen::Isometry3d::Identity()));
  EXPECT_EQ(tracker_.sectionsCut(), 2);
}

TEST_F(GraspObjectTest, OffThePlaneOrBeyondTheFingerIsOutOfReachWithNoContactWork) {
  tracker_.setObject(ball(0.06, 0.03, 0.05, 0.012));  // 5 cm above the bending plane
  ASSERT_TRUE(tracker_.locate(Eigen::Isometry3d::Identity()));
  EXPECT_EQ(tracker_.status(), pf::GraspObjectStatus::kOutOfReach);
  EXPECT_FALSE(tracker_.inReach());
  EXPECT_EQ(tracker_.sectionsCut(), 0);
  tracker_.setObject(ball(0.5, 0.0, 0.0, 0.012));  // half a metre away
  ASSERT_TRUE(tracker_.locate(Eigen::Isometry3d::Identity()));
  EXPECT_EQ(tracker_.status(), pf::GraspObjectStatus::kOutOfReach);
  EXPECT_TRUE(std::isnan(tracker_.touchGaugePa()));
}

TEST_F(GraspObjectTest, AnObjectOnTheStraightFingerIsReportedNotSolved) {
  tracker_.setObject(ball(0.04, 0.0, 0.0, 0.005));
  ASSERT_TRUE(tracker_.locate(Eigen::Isometry3d::Identity()));
  EXPECT_EQ(tracker_.status(), pf::GraspObjectStatus::kOverlapsAtRest);
  EXPECT_NE(tracker_.problem().find("overlaps the straight finger"), std::string::npos) << tracker_.problem();
  EXPECT_EQ(tracker_.statusWith(tracker_.solve(1e5)), pf::GraspObjectStatus::kOverlapsAtRest);
}

TEST_F(GraspObjectTest, ALostTransformIsAStatusUntilThePoseIsKnownAgain) {
  tracker_.setObject(ball(0.06, 0.03, 0.001, 0.012));
  ASSERT_TRUE(tracker_.locate(Eigen::Isometry3d::Identity()));
  EXPECT_TRUE(tracker_.lostTransform("no transform from 'world'"));
  EXPECT_FALSE(tracker_.lostTransform("no transform from 'world'"));  // no change the second time
  EXPECT_EQ(tracker_.status(), pf::GraspObjectStatus::kNoTransform);
  EXPECT_FALSE(tracker_.inReach());
  EXPECT_EQ(tracker_.transformFailures(), 2);
  EXPECT_EQ(tracker_.problem(), "no transform from 'world'");
  EXPECT_TRUE(tracker_.locate(Eigen::Isometry3d::Identity()));  // back: cut again
  EXPECT_EQ(tracker_.status(), pf::GraspObjectStatus::kClear);
  EXPECT_TRUE(tracker_.problem().empty());
  tracker_.clear();
  EXPECT_EQ(tracker_.status(), pf::GraspObjectStatus::kNone);
}
