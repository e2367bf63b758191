// finger_node's grasp object (docs/GRASP.md): a message validated and followed, located in the finger's frame by
// the finger's own mount and tf, and handed to the contact rule's tracker.
#include <cmath>
#include <string>

#include "pneumatic_finger/core/units.hpp"
#include "pneumatic_finger/ros/conversions.hpp"
#include "pneumatic_finger/ros/finger_node.hpp"

namespace pneumatic_finger {

void FingerNode::onGraspObject(const GraspObject::ConstPtr& msg) {
  object_.reset();
  object_refused_.clear();
  grasp_->clear();
  object_timer_.stop();
  // Said once per change: the physics cell sends the object at 50 Hz as it moves, with the same id and frame.
  const std::string said = msg->id.empty() ? "cleared" : "'" + msg->id + "' in '" + msg->header.frame_id + "'";
  if (!msg->id.empty() && !acceptObject(msg)) return republish();
  if (said != announced_object_) ROS_INFO("%s: grasp object %s", log_name_.c_str(), said.c_str());
  announced_object_ = said;
  if (!msg->id.empty()) updateObject();
  republish();
}

bool FingerNode::acceptObject(const GraspObject::ConstPtr& msg) {
  // Validate before use: a bad object is refused by name and the finger stays free.
  std::string why = solidFromMessage(*msg, object_in_frame_);
  if (why.empty() && msg->header.frame_id.empty()) why = "header.frame_id is empty";
  if (!why.empty()) {
    object_refused_ = "grasp object '" + msg->id + "' refused: " + why;
    ROS_ERROR("%s: %s; the finger stays free", log_name_.c_str(), object_refused_.c_str());
    return false;
  }
  object_ = msg;
  object_since_ = ros::WallTime::now();
  object_located_once_ = false;
  grasp_->setObject(object_in_frame_);
  const std::string finger_frame = segmentLinkName(settings_.urdf.prefix, 0);
  if (msg->header.frame_id != finger_frame && msg->header.frame_id != settings_.urdf.parent_frame && !tf_buffer_) {
    tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
    tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_);
  }
  if (!object_timer_.isValid()) {
    object_timer_ = nh_.createTimer(ros::Duration(1.0 / settings_.object_rate_hz), &FingerNode::onObjectTimer, this);
  }
  object_timer_.start();
  return true;
}

void FingerNode::onObjectTimer(const ros::TimerEvent&) {
  if (updateObject()) republish();
}

bool FingerNode::objectPose(Eigen::Isometry3d& finger_from_frame, std::string& why) const {
  const std::string finger_frame = segmentLinkName(settings_.urdf.prefix, 0);
  const std::string& parent_frame = settings_.urdf.parent_frame;
  finger_from_frame = Eigen::Isometry3d::Identity();
  if (object_->header.frame_id == finger_frame) return true;
  // The finger's own mount (known here, not looked up: it does not depend on who publishes the finger's frames)
  // after tf's latest parent_frame <- object frame.
  const auto& xyz = settings_.urdf.mount_xyz_m;
  const auto& rpy = settings_.urdf.mount_rpy_rad;
  const Eigen::Isometry3d parent_from_finger =
      Eigen::Translation3d(xyz[0], xyz[1], xyz[2]) * Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) *
      Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX());
  Eigen::Isometry3d parent_from_frame = Eigen::Isometry3d::Identity();
  if (object_->header.frame_id != parent_frame) {
    geometry_msgs::TransformStamped t;
    try {
      t = tf_buffer_->lookupTransform(parent_frame, object_->header.frame_id, ros::Time(0));
    } catch (const tf2::TransformException& e) {
      why = "no transform from '" + object_->header.frame_id + "' to '" + parent_frame + "': " + e.what();
      return false;
    }
    // tf keeps a dead publisher's last transform for ever: a chain through moving joints (stamp not 0) that has not
    // been renewed for transform_timeout_s is as good as none, or the finger would close on where the object was.
    const double age_s = (ros::Time::now() - t.header.stamp).toSec();
    if (settings_.transform_timeout_s > 0 && !t.header.stamp.isZero() && age_s > settings_.transform_timeout_s) {
      why = "the transform from '" + object_->header.frame_id + "' to '" + parent_frame + "' is " +
            formatMessage(std::round(age_s * 100) / 100) + " s old (over transform_timeout_s): has its publisher stopped?";
      return false;
    }
    parent_from_frame = isometryFromMessage(t.transform);
  }
  finger_from_frame = parent_from_finger.inverse() * parent_from_frame;
  return true;
}

bool FingerNode::updateObject() {
  if (!object_) return false;
  Eigen::Isometry3d finger_from_frame;
  std::string why;
  if (!objectPose(finger_from_frame, why)) {
    // At start-up the frames come a moment after the object (robot_state_publisher's first joint states): that
    // wait is not a problem worth a WARN. A transform still missing after it, or lost later, is.
    const bool starting = !object_located_once_ && (ros::WallTime::now() - object_since_).toSec() < kTransformGraceS;
    if (starting) {
      ROS_DEBUG("%s: grasp object '%s': waiting for tf: %s", log_name_.c_str(), object_->id.c_str(), why.c_str());
    } else {
      ROS_WARN_THROTTLE(5.0, "%s: grasp object '%s': %s", log_name_.c_str(), object_->id.c_str(), why.c_str());
    }
    return grasp_->lostTransform(why);
  }
  object_located_once_ = true;
  const bool changed = grasp_->locate(finger_from_frame);
  if (changed && grasp_->status() == GraspObjectStatus::kOverlapsAtRest) {
    ROS_WARN_THROTTLE(5.0, "%s: grasp object '%s' %s", log_name_.c_str(), object_->id.c_str(), grasp_->problem().c_str());
  }
  return changed;
}

}  // namespace pneumatic_finger
