#include "pneumatic_finger/core/grasp_object.hpp"

#include <cmath>
#include <limits>
#include <optional>

namespace pneumatic_finger {

const char* graspObjectStatusName(GraspObjectStatus status) {
  switch (status) {
    case GraspObjectStatus::kNone: return "none";
    case GraspObjectStatus::kOutOfReach: return "out of reach";
    case GraspObjectStatus::kClear: return "clear (in reach, not touched)";
    case GraspObjectStatus::kTouching: return "touching";
    case GraspObjectStatus::kOverlapsAtRest: return "overlaps the straight finger";
    case GraspObjectStatus::kNoTransform: return "no transform to the object's frame";
  }
  return "unknown";
}

GraspObjectTracker::GraspObjectTracker(const FingerModel& model, double max_gauge_pa)
    : model_(model),
      max_gauge_pa_(max_gauge_pa),
      length_m_(model.parameters().lengthM()),
      touch_gauge_pa_(std::numeric_limits<double>::quiet_NaN()) {}

void GraspObjectTracker::setObject(const SolidObject& solid) {
  clear();
  has_object_ = true;
  in_frame_ = solid;
}

void GraspObjectTracker::clear() {
  has_object_ = located_ = false;
  tracker_.reset();
  status_ = GraspObjectStatus::kNone;
  touch_gauge_pa_ = std::numeric_limits<double>::quiet_NaN();
  problem_.clear();
}

bool GraspObjectTracker::lostTransform(const std::string& why) {
  ++transform_failures_;
  problem_ = why;
  const bool changed = status_ != GraspObjectStatus::kNoTransform;
  status_ = GraspObjectStatus::kNoTransform;
  tracker_.reset();
  located_ = false;
  return changed;
}

bool GraspObjectTracker::locate(const Eigen::Isometry3d& finger_from_frame) {
  if (!has_object_) return false;
  SolidObject solid = in_frame_;
  solid.pose = finger_from_frame * in_frame_.pose;
  // Unchanged pose relative to the finger (a still arm and object): the tracker and its touch events stay.
  if (located_ && solid.pose.matrix() == in_finger_.pose.matrix()) return false;
  in_finger_ = solid;
  located_ = true;
  problem_.clear();
  tracker_.reset();
  touch_gauge_pa_ = std::numeric_limits<double>::quiet_NaN();
  // Out of reach (the bounding sphere beyond the finger's length, or off its plane): no section, no contact work.
  const Eigen::Vector3d c = solid.pose.translation();
  const double r = solid.boundingRadius();
  std::optional<Obstacle> section;
  if (c.norm() - r <= length_m_ && std::fabs(c.z()) < r) section = sectionByFingerPlane(solid);
  if (!section || section->distanceFromOrigin() > length_m_) {
    status_ = GraspObjectStatus::kOutOfReach;
    return true;
  }
  ++sections_cut_;
  tracker_ = std::make_unique<ContactTracker>(model_, *section);
  // The whole range at once: the first touch is then known (for the gripper action), and every pressure after this
  // is answered from the kept events.
  const ContactState full = tracker_->solve(max_gauge_pa_);
  touch_gauge_pa_ = full.first_touch_gauge_pa;
  const bool overlaps = full.status == ContactState::Status::kOverlapsAtRest;
  status_ = overlaps ? GraspObjectStatus::kOverlapsAtRest : GraspObjectStatus::kClear;
  if (overlaps) problem_ = "overlaps the straight finger: reported, not solved";
  return true;
}

GraspObjectStatus GraspObjectTracker::statusWith(const ContactState& contact) const {
  switch (contact.status) {
    case ContactState::Status::kInContact: return GraspObjectStatus::kTouching;
    case ContactState::Status::kOverlapsAtRest: return GraspObjectStatus::kOverlapsAtRest;
    default: return GraspObjectStatus::kClear;
  }
}

}  // namespace pneumatic_finger
