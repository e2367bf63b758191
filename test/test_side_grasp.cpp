// Where the cell holds its cylinder (src/cell/side_grasp.cpp): at the computed depth every finger closes on the
// side, away from both rims. The check is independent of the construction (an endless cylinder's side): the real,
// finite cylinder at that depth, cut by each finger's plane, and the finger closed on it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pneumatic_finger/cell/side_grasp.hpp"
#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/object_section.hpp"

namespace pf = pneumatic_finger;

namespace {

const std::string kGripper = std::string(PACKAGE_SOURCE_DIR) + "/config/gripper.yaml";
constexpr double kRadius = 0.016, kHeight = 0.035;  // config/cell.yaml's cylinder

Eigen::Isometry3d mount(const pf::FingerUrdfOptions& m) {
  Eigen::Isometry3d pose(Eigen::Translation3d(m.mount_xyz_m[0], m.mount_xyz_m[1], m.mount_xyz_m[2]));
  pose.rotate(Eigen::AngleAxisd(m.mount_rpy_rad[2], Eigen::Vector3d::UnitZ()) *
              Eigen::AngleAxisd(m.mount_rpy_rad[1], Eigen::Vector3d::UnitY()) *
              Eigen::AngleAxisd(m.mount_rpy_rad[0], Eigen::Vector3d::UnitX()));
  return pose;
}

// The first touch of @p finger on the finite cylinder centred at @p depth_m on tool z, in the cylinder's frame.
Eigen::Vector3d firstTouch(const pf::GripperFinger& finger, double depth_m) {
  const Eigen::Isometry3d tool_from_finger = mount(finger.mount);
  const Eigen::Isometry3d tool_from_cylinder(Eigen::Translation3d(0, 0, depth_m));
  pf::SolidObject cylinder;
  cylinder.shape = pf::SolidObject::Shape::kCylinder;
  cylinder.radius_m = kRadius;
  cylinder.height_m = kHeight;
  cylinder.pose = tool_from_finger.inverse() * tool_from_cylinder;
  const auto section = pf::sectionByFingerPlane(cylinder);
  EXPECT_TRUE(section.has_value());
  const pf::FingerModel model(finger.parameters);
  const pf::ContactState s = pf::ContactSolver(model).solve(finger.mount.max_gauge_pa, *section);
  EXPECT_EQ(s.status, pf::ContactState::Status::kInContact);
  EXPECT_FALSE(s.contact_points_m.empty());
  const Eigen::Vector2d p = s.contact_points_m.front();
  return tool_from_cylinder.inverse() * tool_from_finger * Eigen::Vector3d(p.x(), p.y(), 0.0);
}

}  // namespace

TEST(SideGrasp, AtTheComputedDepthEveryFingerTouchesTheSideAwayFromTheRims) {
  const auto fingers = pf::loadGripperFile(kGripper);
  const pf::SideGrasp g = pf::sideGraspDepth(fingers, kRadius, kHeight);
  ASSERT_EQ(g.touch_depth_m.size(), fingers.size());
  EXPECT_GT(g.rim_margin_m, 0.01) << "every touch at least 10 mm from a rim";
  for (const auto& f : fingers) {
    const Eigen::Vector3d touch = firstTouch(f, g.centre_depth_m);
    EXPECT_NEAR(std::hypot(touch.x(), touch.y()), kRadius, 1e-6) << f.mount.prefix << ": on the side's surface";
    EXPECT_LT(std::fabs(touch.z()), 0.5 * kHeight - 0.01) << f.mount.prefix << ": more than 10 mm from a rim";
  }
}

// The depth the cell typed before (75 mm): the fingers' tips meet the bottom rim, a pinch on the edge.
TEST(SideGrasp, TheFormerTypedDepthPinchesTheBottomRim) {
  for (const auto& f : pf::loadGripperFile(kGripper)) {
    const Eigen::Vector3d touch = firstTouch(f, 0.075);
    EXPECT_NEAR(touch.z(), 0.5 * kHeight, 0.002) << f.mount.prefix << ": at the bottom face";
  }
}

TEST(SideGrasp, ACylinderOutOfReachIsRefusedNamingTheFinger) {
  auto fingers = pf::loadGripperFile(kGripper);
  fingers[0].mount.max_gauge_pa = 1000.0;  // barely bends: finger_a cannot reach the side
  try {
    pf::sideGraspDepth(fingers, kRadius, kHeight);
    FAIL() << "a cylinder the fingers cannot reach was accepted";
  } catch (const pf::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("finger 'finger_a_' does not reach the side"), std::string::npos) << e.what();
  }
}
