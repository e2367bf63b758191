#include "pneumatic_finger/cell/side_grasp.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/grasp_object.hpp"
#include "pneumatic_finger/core/object_section.hpp"

namespace pneumatic_finger {

namespace {

Eigen::Isometry3d mountPose(const FingerUrdfOptions& m) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(Eigen::Vector3d(m.mount_xyz_m[0], m.mount_xyz_m[1], m.mount_xyz_m[2]));
  // URDF's fixed-axis roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll).
  pose.rotate(Eigen::AngleAxisd(m.mount_rpy_rad[2], Eigen::Vector3d::UnitZ()) *
              Eigen::AngleAxisd(m.mount_rpy_rad[1], Eigen::Vector3d::UnitY()) *
              Eigen::AngleAxisd(m.mount_rpy_rad[0], Eigen::Vector3d::UnitX()));
  return pose;
}

// Where one finger first meets the side of an endless cylinder on tool z: the depth along tool z and the pressure.
bool sideTouch(const GripperFinger& finger, double radius_m, double& depth_m, double& gauge_pa) {
  const Eigen::Isometry3d tool_from_finger = mountPose(finger.mount);
  const FingerModel model(finger.parameters);
  // Tall enough that no rim lies within the finger's reach around its mount.
  const double reach_m = finger.parameters.lengthM() + tool_from_finger.translation().norm();
  SolidObject side;
  side.shape = SolidObject::Shape::kCylinder;
  side.radius_m = radius_m;
  side.height_m = 4.0 * reach_m;
  side.pose = tool_from_finger.inverse();  // the cylinder's frame is the tool's: centred on tool z at the tool frame
  const auto section = sectionByFingerPlane(side);
  if (!section) return false;
  const ContactState touched = ContactSolver(model).solve(finger.mount.max_gauge_pa, *section);
  if (touched.status != ContactState::Status::kInContact || touched.contact_points_m.empty()) return false;
  const Eigen::Vector2d p = touched.contact_points_m.front();
  depth_m = (tool_from_finger * Eigen::Vector3d(p.x(), p.y(), 0.0)).z();
  gauge_pa = touched.first_touch_gauge_pa;
  return true;
}

}  // namespace

SideGrasp sideGraspDepth(const std::vector<GripperFinger>& fingers, double radius_m, double height_m) {
  SideGrasp g;
  for (const GripperFinger& f : fingers) {
    double depth = 0.0, gauge = 0.0;
    if (!sideTouch(f, radius_m, depth, gauge)) {
      throw ParameterError("finger '" + f.mount.prefix + "' does not reach the side of a cylinder of radius " +
                           formatMessage(radius_m) + " m on the gripper axis up to " +
                           formatMessage(f.mount.max_gauge_pa) + " Pa");
    }
    g.touch_depth_m.push_back(depth);
    g.touch_pressure_pa.push_back(gauge);
  }
  const auto [lo, hi] = std::minmax_element(g.touch_depth_m.begin(), g.touch_depth_m.end());
  g.centre_depth_m = 0.5 * (*lo + *hi);
  g.rim_margin_m = 0.5 * height_m - 0.5 * (*hi - *lo);
  if (!(g.rim_margin_m > 0.0)) {
    std::ostringstream why;
    why << "the fingers meet the cylinder's side at depths from " << *lo << " to " << *hi << " m: more than its height "
        << height_m << " m, so no depth puts every touch on the side";
    throw ParameterError(why.str());
  }
  return g;
}

SideGraspForces sideGraspForces(const std::vector<GripperFinger>& fingers, double radius_m, double height_m,
                                double centre_depth_m, double gauge_pa) {
  SideGraspForces out;
  SolidObject cylinder;
  cylinder.shape = SolidObject::Shape::kCylinder;
  cylinder.radius_m = radius_m;
  cylinder.height_m = height_m;
  for (const GripperFinger& f : fingers) {
    const FingerModel model(f.parameters);
    GraspObjectTracker tracker(model, f.mount.max_gauge_pa);
    tracker.setObject(cylinder);
    tracker.locate(mountPose(f.mount).inverse() * Eigen::Translation3d(0.0, 0.0, centre_depth_m));
    out.touch_gauge_pa.push_back(tracker.touchGaugePa());
    out.normal_force_n.push_back(tracker.inReach() ? totalContactForceN(model, gauge_pa, tracker.solve(gauge_pa)) : 0.0);
  }
  return out;
}

}  // namespace pneumatic_finger
