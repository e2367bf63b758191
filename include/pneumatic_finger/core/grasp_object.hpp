// The grasp object as one finger sees it: from the object's pose in the finger's frame to its section by the bending
// plane, the contact rule's touch events, a status and the predicted first touch (docs/GRASP.md). ROS-free: the node
// looks the pose up (tf) and forwards it here; a unit test drives it with poses of its own.
#pragma once

#include <Eigen/Geometry>

#include <memory>
#include <string>

#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/object_section.hpp"

namespace pneumatic_finger {

/// What a finger makes of its grasp object; the same order as finger_state's OBJECT_* constants.
enum class GraspObjectStatus {
  kNone,            ///< no object: the free finger
  kOutOfReach,      ///< the object misses the bending plane or lies beyond the finger's length: no contact work
  kClear,           ///< within reach, not touched at this pressure
  kTouching,        ///< touched: some joints are held
  kOverlapsAtRest,  ///< the object overlaps the straight finger: reported, not solved (the free finger)
  kNoTransform,     ///< the object's frame cannot be related to the finger's yet: the free finger
};

/// "none", "out of reach", "clear (in reach, not touched)", "touching", "overlaps the straight finger", "no transform
/// to the object's frame": as diagnostics show it.
const char* graspObjectStatusName(GraspObjectStatus status);

class GraspObjectTracker {
 public:
  /// @param model the finger (kept by reference: it must outlive the tracker)
  /// @param max_gauge_pa the top of the pressure range: the predicted first touch is searched up to it
  GraspObjectTracker(const FingerModel& model, double max_gauge_pa);

  /// A new object, @p solid given in its own frame (its pose there); the previous one is forgotten.
  void setObject(const SolidObject& solid);
  /// No object: the free finger.
  void clear();

  /// The pose of the object's frame in the finger's frame (segment_0: x along the unbent finger, y toward the
  /// strain-limited side, z normal to the bending plane). An unchanged pose keeps the touch events; a new one cuts the
  /// object by the plane again. @return whether the status or the section changed.
  bool locate(const Eigen::Isometry3d& finger_from_frame);
  /// The object's frame could not be related to the finger's (@p why): status kNoTransform, until locate() succeeds.
  /// @return whether the status changed.
  bool lostTransform(const std::string& why);

  /// The contact rule applies: a section within reach (overlapping the straight finger too: the rule says so).
  bool inReach() const { return tracker_ && !tracker_->outOfReach(); }
  /// The finger at @p gauge_pa with the object (only when inReach()).
  ContactState solve(double gauge_pa) { return tracker_->solve(gauge_pa); }
  /// The status without a pressure (kNone, kOutOfReach, kClear, kOverlapsAtRest or kNoTransform) and with @p contact,
  /// the contact rule's answer at a pressure.
  GraspObjectStatus status() const { return status_; }
  GraspObjectStatus statusWith(const ContactState& contact) const;

  /// The predicted first touch over the whole range (Pa gauge); NaN when there is none.
  double touchGaugePa() const { return touch_gauge_pa_; }
  /// How many sections were cut (each new pose of the object in the finger's frame), and transforms missed.
  long sectionsCut() const { return sections_cut_; }
  long transformFailures() const { return transform_failures_; }
  /// The last problem with the object (no transform, overlap at rest), empty when there is none.
  const std::string& problem() const { return problem_; }

 private:
  const FingerModel& model_;
  double max_gauge_pa_;
  double length_m_;
  bool has_object_ = false, located_ = false;
  SolidObject in_frame_, in_finger_;
  std::unique_ptr<ContactTracker> tracker_;  ///< null: no section in reach
  GraspObjectStatus status_ = GraspObjectStatus::kNone;
  double touch_gauge_pa_;
  long sections_cut_ = 0, transform_failures_ = 0;
  std::string problem_;
};

}  // namespace pneumatic_finger
