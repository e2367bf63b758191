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


}  // namespace pneumatic_finger
