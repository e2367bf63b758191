// Between finger_node's messages and the core's types.
#pragma once

#include <Eigen/Geometry>
#include <geometry_msgs/Transform.h>
#include <visualization_msgs/MarkerArray.h>

#include <cstdint>
#include <string>
#include <vector>

#include "pneumatic_finger/FingerModelState.h"
#include "pneumatic_finger/GraspObject.h"
#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/evaluation.hpp"
#include "pneumatic_finger/core/evaluation_report.hpp"
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

/// rviz's picture of the contact forces, in @p frame_id (the finger's mount frame, where the contact state lives): a
/// DELETEALL for the namespace @p ns, then one arrow per contact point, pointing at the object along its segment's
/// normal and ending at the point, @p metres_per_newton long per newton of @p force_n (the force the finger presses
/// with), @p side_offset_m across the bending plane (beside the finger, which would hide it).
visualization_msgs::MarkerArray contactForceArrows(const ContactState& contact, const std::vector<double>& force_n,
                                                   const std::string& frame_id, const std::string& ns,
                                                   double metres_per_newton, double side_offset_m);

}  // namespace pneumatic_finger
