// The grasp object the rostests publish: a sphere, since its section by any finger's plane through its centre is a
// disk of its own radius, the obstacle the core's contact is checked with.
#pragma once

#include <shape_msgs/SolidPrimitive.h>

#include <string>

#include "pneumatic_finger/GraspObject.h"

namespace pf_test {

/// A sphere of @p radius_m named @p id, centred at (@p x_m, @p y_m, @p z_m) in @p frame, unrotated.
inline pneumatic_finger::GraspObject sphereObject(const std::string& frame, const std::string& id, double radius_m,
                                                  double x_m, double y_m, double z_m = 0.0) {
  pneumatic_finger::GraspObject o;
  o.header.frame_id = frame;
  o.id = id;
  o.shape.type = shape_msgs::SolidPrimitive::SPHERE;
  o.shape.dimensions = {radius_m};
  o.pose.position.x = x_m, o.pose.position.y = y_m, o.pose.position.z = z_m;
  o.pose.orientation.w = 1.0;
  return o;
}

}  // namespace pf_test
