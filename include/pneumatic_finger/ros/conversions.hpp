// Between finger_node's messages and the core's types.
#pragma once

#include <Eigen/Geometry>
#include <geometry_msgs/Transform.h>

#include <cstdint>
#include <string>

#include "pneumatic_finger/FingerModelState.h"
#include "pneumatic_finger/GraspObject.h"
#include "pneumatic_finger/core/grasp_object.hpp"
#include "pneumatic_finger/core/object_section.hpp"

namespace pneumatic_finger {

/// finger_state's object_status for a GraspObjectStatus.
std::uint8_t toMessage(GraspObjectStatus status);

/// A transform message as an isometry.
Eigen::Isometry3d isometryFromMessage(const geometry_msgs::Transform& t);

/// The solid a GraspObject message describes, in its own frame, into @p solid. @return why it is not valid, empty
/// when it is.
std::string solidFromMessage(const GraspObject& msg, SolidObject& solid);

}  // namespace pneumatic_finger
