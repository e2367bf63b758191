#include "pneumatic_finger/ros/conversions.hpp"

#include <cmath>
#include <string>

namespace pneumatic_finger {

// finger_state's OBJECT_* constants are the core's GraspObjectStatus, in the same order.
static_assert(FingerModelState::OBJECT_NONE == static_cast<int>(GraspObjectStatus::kNone) &&
                  FingerModelState::OBJECT_OUT_OF_REACH == static_cast<int>(GraspObjectStatus::kOutOfReach) &&
                  FingerModelState::OBJECT_CLEAR == static_cast<int>(GraspObjectStatus::kClear) &&
                  FingerModelState::OBJECT_TOUCHING == static_cast<int>(GraspObjectStatus::kTouching) &&
                  FingerModelState::OBJECT_OVERLAPS_AT_REST == static_cast<int>(GraspObjectStatus::kOverlapsAtRest) &&
                  FingerModelState::OBJECT_NO_TRANSFORM == static_cast<int>(GraspObjectStatus::kNoTransform),
              "msg/FingerModelState.msg's OBJECT_* follow GraspObjectStatus");
std::uint8_t toMessage(GraspObjectStatus status) { return static_cast<std::uint8_t>(status); }

// finger_state's STATUS_* constants are the core's EvaluationStatus codes: one list, with Python's pf.STATUS.
static_assert(FingerModelState::STATUS_OK == static_cast<int>(EvaluationStatus::kOk) &&
                  FingerModelState::STATUS_VACUUM == static_cast<int>(EvaluationStatus::kVacuum) &&
                  FingerModelState::STATUS_CLAMPED == static_cast<int>(EvaluationStatus::kClamped) &&
                  FingerModelState::STATUS_BEYOND_LIMIT_POINT == static_cast<int>(EvaluationStatus::kBeyondLimitPoint) &&
                  FingerModelState::STATUS_SNAPPED_THROUGH == static_cast<int>(EvaluationStatus::kSnappedThrough) &&
                  FingerModelState::STATUS_NOT_FINITE == static_cast<int>(EvaluationStatus::kNotFinite) &&
                  FingerModelState::STATUS_SOLVER_FAILURE == static_cast<int>(EvaluationStatus::kSolverFailure) &&
                  FingerModelState::STATUS_MEETS_ITSELF == static_cast<int>(EvaluationStatus::kMeetsItself) &&
                  kEvaluationStatusCount == 8,
              "msg/FingerModelState.msg's STATUS_* are EvaluationStatus's codes, all of them");
static_assert(FingerModelState::FLAG_CLAMPED == kFlagClamped && FingerModelState::FLAG_FAR_BRANCH == kFlagFarBranch &&
                  FingerModelState::FLAG_MEETS_ITSELF == kFlagMeetsItself &&
                  FingerModelState::FLAG_EXTRAPOLATED == kFlagExtrapolated && kStatusFlagCount == 4,
              "msg/FingerModelState.msg's FLAG_* are StatusFlag's bits, all of them");

Eigen::Isometry3d isometryFromMessage(const geometry_msgs::Transform& t) {
  return Eigen::Translation3d(t.translation.x, t.translation.y, t.translation.z) *
         Eigen::Quaterniond(t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z);
}

// The solid a GraspObject message describes, in its own frame; the reason it is not valid, empty when it is.
std::string solidFromMessage(const GraspObject& msg, SolidObject& solid) {
  const auto& d = msg.shape.dimensions;
  using Prim = shape_msgs::SolidPrimitive;
  if (msg.shape.type == Prim::BOX && d.size() == 3) {
    solid.shape = SolidObject::Shape::kBox;
    solid.box_size_m = Eigen::Vector3d(d[Prim::BOX_X], d[Prim::BOX_Y], d[Prim::BOX_Z]);
  } else if (msg.shape.type == Prim::SPHERE && d.size() == 1) {
    solid.shape = SolidObject::Shape::kSphere;
    solid.radius_m = d[Prim::SPHERE_RADIUS];
  } else if (msg.shape.type == Prim::CYLINDER && d.size() == 2) {
    solid.shape = SolidObject::Shape::kCylinder;
    solid.height_m = d[Prim::CYLINDER_HEIGHT];
    solid.radius_m = d[Prim::CYLINDER_RADIUS];
  } else {
    return "shape type " + std::to_string(msg.shape.type) + " with " + std::to_string(d.size()) +
           " dimensions is not a BOX (3), SPHERE (1) or CYLINDER (2)";
  }
  const auto& o = msg.pose.orientation;
  const Eigen::Quaterniond rotation(o.w, o.x, o.y, o.z);
  if (!(std::fabs(rotation.norm() - 1.0) <= 1e-6)) return "the pose's orientation is not a unit quaternion";
  solid.pose = Eigen::Translation3d(msg.pose.position.x, msg.pose.position.y, msg.pose.position.z) *
               rotation.normalized();
  return solid.problem();
}


visualization_msgs::MarkerArray contactForceArrows(const ContactState& contact, const std::vector<double>& force_n,
                                                   const std::string& frame_id, const std::string& ns,
                                                   double metres_per_newton, double side_offset_m) {
  visualization_msgs::MarkerArray out;
  visualization_msgs::Marker clear;
  clear.header.frame_id = frame_id;
  clear.ns = ns;
  clear.action = visualization_msgs::Marker::DELETEALL;
  out.markers.push_back(clear);
  for (std::size_t k = 0; k < force_n.size() && k < contact.contact_points_m.size(); ++k) {
    if (!std::isfinite(force_n[k]) || force_n[k] <= 0) continue;
    const auto m = static_cast<Eigen::Index>(contact.contact_segments.at(k));
    const Eigen::Vector2d d = (contact.backbone_m.col(m + 1) - contact.backbone_m.col(m)).normalized();
    // Drawn on the finger's side, ending at the contact point, and beside the finger (side_offset_m across its width):
    // the object would hide an arrow inside it, and the finger's body one within it.
    const Eigen::Vector2d to = contact.contact_points_m[k];
    const Eigen::Vector2d from = to - force_n[k] * metres_per_newton * Eigen::Vector2d(-d.y(), d.x());
    visualization_msgs::Marker a;
    a.header.frame_id = frame_id;
    a.ns = ns;
    a.id = static_cast<int>(k);
    a.type = visualization_msgs::Marker::ARROW;
    a.action = visualization_msgs::Marker::ADD;
    a.pose.orientation.w = 1.0;
    a.frame_locked = true;
    geometry_msgs::Point p0, p1;
    p0.x = from.x(), p0.y = from.y(), p1.x = to.x(), p1.y = to.y();
    p0.z = p1.z = side_offset_m;
    a.points = {p0, p1};
    a.scale.x = 0.002, a.scale.y = 0.004, a.scale.z = 0.004;  // shaft and head diameters, head length (m)
    a.color.r = 1.0f, a.color.g = 0.25f, a.color.b = 0.1f, a.color.a = 1.0f;
    out.markers.push_back(a);
  }
  return out;
}

}  // namespace pneumatic_finger
