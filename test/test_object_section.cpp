// The section of a box, sphere or cylinder by the finger's plane, against an independent reference: points of the
// plane z = 0 tested for being inside the 3D solid with its own definition (|R^T (p - c)| within the half sizes,
// the radius, the height), compared with Obstacle::contains on the section.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pneumatic_finger/core/object_section.hpp"

namespace pf = pneumatic_finger;

namespace {

// Signed distance-like depth of a plane point inside the 3D solid: > 0 inside, < 0 outside (in metres, exact
// for the box along its axes and for the sphere; for the cylinder the smaller of the radial and axial margins).
double depthInSolid(const pf::SolidObject& s, const Eigen::Vector3d& world) {
  const Eigen::Vector3d p = s.pose.inverse() * world;
  switch (s.shape) {
    case pf::SolidObject::Shape::kBox:
      return (0.5 * s.box_size_m - p.cwiseAbs()).minCoeff();
    case pf::SolidObject::Shape::kSphere:
      return s.radius_m - p.norm();
    case pf::SolidObject::Shape::kCylinder:
      return std::min(s.radius_m - std::hypot(p.x(), p.y()), 0.5 * s.height_m - std::fabs(p.z()));
  }
  return 0;
}

Eigen::Isometry3d pose(double x, double y, double z, double rx, double ry, double rz) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translate(Eigen::Vector3d(x, y, z));
  t.rotate(Eigen::AngleAxisd(rz, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(ry, Eigen::Vector3d::UnitY()) *
           Eigen::AngleAxisd(rx, Eigen::Vector3d::UnitX()));
  return t;
}

// Every plane point clearly inside the solid (by more than margin) is inside the section; every point clearly
// outside is outside it.
void expectSectionMatches(const pf::SolidObject& s, double margin_m, int* inside_count = nullptr) {
  const auto section = pf::sectionByFingerPlane(s);
  ASSERT_TRUE(section.has_value());
  EXPECT_EQ(section->problem(), "");
  std::mt19937 rng(7);
  const double r = s.boundingRadius();
  std::uniform_real_distribution<double> ux(s.pose.translation().x() - r, s.pose.translation().x() + r);
  std::uniform_real_distribution<double> uy(s.pose.translation().y() - r, s.pose.translation().y() + r);
  int inside = 0;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3d p(ux(rng), uy(rng), 0.0);
    const double depth = depthInSolid(s, p);
    if (depth > margin_m) {
      ++inside;
      EXPECT_TRUE(section->contains(p.head<2>())) << "(" << p.x() << ", " << p.y() << ") depth " << depth;
    } else if (depth < -margin_m) {
      EXPECT_FALSE(section->contains(p.head<2>())) << "(" << p.x() << ", " << p.y() << ") depth " << depth;
    }
  }
  EXPECT_GT(inside, 1000);  // the comparison saw the section's inside, not only its outside
  if (inside_count) *inside_count = inside;
}

}  // namespace

TEST(ObjectSection, SphereCutOffCentreIsTheDiskOfThePlane) {
  pf::SolidObject s;
  s.shape = pf::SolidObject::Shape::kSphere;
  s.radius_m = 0.02;
  s.pose = pose(0.05, 0.03, 0.012, 0.3, 0.2, 0.1);
  expectSectionMatches(s, 1e-12);
  s.pose = pose(0.05, 0.03, 0.02, 0, 0, 0);  // tangent: a point, no section
  EXPECT_FALSE(pf::sectionByFingerPlane(s).has_value());
}

TEST(ObjectSection, BoxAtAnyOrientationIsItsPolygon) {
  pf::SolidObject s;
  s.shape = pf::SolidObject::Shape::kBox;
  s.box_size_m = Eigen::Vector3d(0.04, 0.025, 0.03);
  for (const auto& t : {pose(0.06, 0.02, 0.0, 0, 0, 0.4), pose(0.06, 0.02, 0.005, 0.7, 0.3, 1.1),
                        pose(0.06, 0.02, -0.009, 1.2, -0.5, 0.2), pose(0.06, 0.02, 0.0, M_PI / 2, 0, 0)}) {
    s.pose = t;
    expectSectionMatches(s, 1e-12);
  }
  s.pose = pose(0.06, 0.02, 0.015, 0, 0, 0);  // the box standing on the plane: the section is its bottom face
  const auto face = pf::sectionByFingerPlane(s);
  ASSERT_TRUE(face.has_value());
  EXPECT_TRUE(face->contains(Eigen::Vector2d(0.06 + 0.0199, 0.02 - 0.0124)));
  EXPECT_FALSE(face->contains(Eigen::Vector2d(0.06 + 0.0201, 0.02)));
  s.pose = pose(0.06, 0.02, 0.0, 0, M_PI / 4, 0);  // tilted 45 degrees about y: a rectangle again
  expectSectionMatches(s, 1e-12);
  s.pose = pose(0.06, 0.02, 0.05, 0, 0, 0);
  EXPECT_FALSE(pf::sectionByFingerPlane(s).has_value());
}

TEST(ObjectSection, CylinderAcrossAlongAndSlantedIncludingThroughACap) {
  pf::SolidObject s;
  s.shape = pf::SolidObject::Shape::kCylinder;
  s.radius_m = 0.016;
  s.height_m = 0.035;
  pf::SectionAccuracy accuracy;
  // Axis normal to the plane: a disk; in the plane (the cell's grasp): a rectangle; slanted inside the caps: an
  // ellipse. All exact.
  for (const auto& t : {pose(0.07, 0.03, 0.004, 0, 0, 0), pose(0.07, 0.03, 0.0, 0, M_PI / 2, 0.3),
                        pose(0.07, 0.03, 0.006, 0, M_PI / 2, -0.2), pose(0.07, 0.03, 0.002, 0.4, 0.2, 0.0)}) {
    s.pose = t;
    ASSERT_TRUE(pf::sectionByFingerPlane(s, &accuracy).has_value());
    EXPECT_EQ(accuracy, pf::SectionAccuracy::kExact);
    expectSectionMatches(s, 1e-12);
  }
  // Slanted through a cap (and nearly parallel to the plane): polygonized, inside the true section by < 0.3 um.
  for (const auto& t : {pose(0.07, 0.03, 0.004, 0.9, 0.4, 0.0), pose(0.07, 0.03, 0.003, 0, M_PI / 2 - 1e-6, 0)}) {
    s.pose = t;
    ASSERT_TRUE(pf::sectionByFingerPlane(s, &accuracy).has_value());
    EXPECT_EQ(accuracy, pf::SectionAccuracy::kPolygonized);
    expectSectionMatches(s, 3e-7);
  }
  s.pose = pose(0.07, 0.03, 0.05, 0, 0, 0);  // beyond both caps
  EXPECT_FALSE(pf::sectionByFingerPlane(s).has_value());
}

TEST(ObjectSection, BadSolidsAreNamed) {
  pf::SolidObject s;
  s.shape = pf::SolidObject::Shape::kCylinder;
  s.radius_m = 0.01;
  s.height_m = -1;
  EXPECT_EQ(s.problem(), "a cylinder's height and radius must be finite and > 0");
  s.shape = pf::SolidObject::Shape::kBox;
  EXPECT_EQ(s.problem(), "a box's three sizes must be finite and > 0");
  s.shape = pf::SolidObject::Shape::kSphere;
  s.radius_m = NAN;
  EXPECT_EQ(s.problem(), "a sphere's radius must be finite and > 0");
  s.radius_m = 0.01;
  s.pose.linear() *= 2.0;
  EXPECT_EQ(s.problem(), "the pose's rotation is not a rotation (its orientation quaternion is not unit)");
}
