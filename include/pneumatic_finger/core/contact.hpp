// The finger closing on an object: a kinematic contact rule on top of the free model (docs/GRASP.md). ROS-free.
//
// In the finger's bending plane (x along the unbent finger from the mount, y toward the strain-limited side, where
// the backbone runs) an obstacle is a convex region. As the pressure rises from 0, every joint follows its free
// angle q_n(p) until the backbone O_0..O_{N+1} would enter the obstacle. At that first touch, at pressure p*, let
// segment m (O_m -> O_{m+1}, moved by joints 1..m) be the segment that touches: every still-free joint up to m
// freezes at its angle at p*. Later joints go on following q_n(p), and the rule repeats up to the pressure asked
// for. No force is modelled: nothing in the model or in the data gives one.
#pragma once

#include <Eigen/Core>

#include <limits>
#include <string>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"

namespace pneumatic_finger {

/// A convex region of the finger's plane: a disk (the section of a sphere or of a cylinder across its axis), a convex
/// polygon (of a box), or an ellipse (of a cylinder cut at a slant).
class Obstacle {
 public:
  static Obstacle disk(double x_m, double y_m, double radius_m);
  /// @param vertices_m the corners in order (either direction); must be convex, at least 3.
  static Obstacle polygon(const std::vector<Eigen::Vector2d>& vertices_m);
  /// @param angle_rad the direction of the @p a_m semi-axis from +x.
  static Obstacle ellipse(double x_m, double y_m, double a_m, double b_m, double angle_rad);

  /// How far the segment @p p -> @p q is from the region: > 0 apart (for a disk the distance, otherwise a
  /// continuous quantity that is 0 exactly when they touch), <= 0 touching or overlapping.
  double clearance(const Eigen::Vector2d& p, const Eigen::Vector2d& q) const;

  /// The point of the segment p -> q nearest the region (the contact point when they touch).
  Eigen::Vector2d nearestPoint(const Eigen::Vector2d& p, const Eigen::Vector2d& q) const;

  /// Radius of a disk around the origin that contains the region's nearest point: the region is out of reach of
  /// a finger of length L when distanceFromOrigin() > L.
  double distanceFromOrigin() const;

  /// For a disk: its centre and radius, and true; false for the other shapes.
  bool asDisk(Eigen::Vector2d& center_m, double& radius_m) const {
    center_m = center_;
    radius_m = radius_;
    return kind_ == Kind::kDisk;
  }

  /// Whether the segment @p p -> @p q touches or enters the region (clearance <= 0, without the square root for a
  /// disk).
  bool touches(const Eigen::Vector2d& p, const Eigen::Vector2d& q) const;

  /// Whether @p p lies inside the region or on its boundary.
  bool contains(const Eigen::Vector2d& p) const { return clearance(p, p) <= 0; }

  /// Why the obstacle is not valid (not finite, radius <= 0, polygon not convex), empty when it is.
  std::string problem() const;

 private:
  enum class Kind { kDisk, kPolygon, kEllipse } kind_ = Kind::kDisk;
  Eigen::Vector2d center_ = Eigen::Vector2d::Zero();
  double radius_ = 0.0, a_ = 0.0, b_ = 0.0, cos_ = 1.0, sin_ = 0.0;
  std::vector<Eigen::Vector2d> vertices_;
};

/// Joint angles and backbone points with their storage inside the object (at most kMaxChamberCount joints): a solve
/// allocates only its list of contact points and of held joints.
using JointAngles = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxChamberCount, 1>;
using BackbonePoints = Eigen::Matrix<double, 2, Eigen::Dynamic, Eigen::ColMajor, 2, kMaxChamberCount + 2>;

/// The finger's shape with an obstacle.
struct ContactState {
  enum class Status {
    kFree,            ///< no touch up to this pressure (or out of reach): the free finger
    kInContact,       ///< at least one joint is held by the obstacle
    kOverlapsAtRest,  ///< the obstacle overlaps the straight finger: reported, not solved (the free finger is given)
    kSolverFailure,   ///< the model found no finite answer
  };
  Status status = Status::kFree;
  JointAngles joint_angle_rad;         ///< q_1..q_N as the contact rule gives them (rad)
  BackbonePoints backbone_m;           ///< O_0..O_{N+1} (m)
  std::vector<bool> held;              ///< per joint: frozen by contact
  std::vector<Eigen::Vector2d> contact_points_m;  ///< where the backbone touches (one per touch event)
  double first_touch_gauge_pa = std::numeric_limits<double>::quiet_NaN();  ///< p* of the first touch (NaN: none)
  int touches = 0;                     ///< touch events solved
};

/// Applies the contact rule to a model. Holds no state of its own: safe beside the model's other const users.
class ContactSolver {
 public:
  explicit ContactSolver(const FingerModel& model);

  /// The finger at @p gauge_pa with @p obstacle, found from scratch (ContactTracker keeps what it found).
  ContactState solve(double gauge_pa, const Obstacle& obstacle) const;

  /// The touch pressures are found to this relative precision (angles follow to about 1e-14 rad).
  static constexpr double kRelativePressureTolerance = 1e-15;
  /// Identical chambers and the robust solver search in the walls' half angle, to this relative precision.
  static constexpr double kRelativeHalfAngleTolerance = 1e-15;

 private:
  friend class ContactTracker;
  /// One touch event: the joints 1..frozen held at frozen_q from gauge_pa on.
  struct Event {
    bool found = false, failed = false;
    double gauge_pa = 0.0;
    double half_angle_rad = 0.0;  ///< the free walls' half angle at the touch (the uniform search)
    int frozen = 0;
    JointAngles frozen_q;
    Eigen::Vector2d point_m = Eigen::Vector2d::Zero();
  };
  /// The first touch after @p from with joints 1..@p frozen held, searched up to sqrt(p) = @p u_end (one grid step
  /// past it at most). Not found: @p u_clear is how far the search went clear.
  Event findEvent(const Obstacle& obstacle, double from, int frozen, const JointAngles& frozen_q, double u_end,
                  double& u_clear) const;
  /// The same for identical chambers and the robust solver, searched in the free walls' half angle from
  /// @p from_half_angle_rad up to @p end_half_angle_rad (clear: @p clear_half_angle_rad is how far).
  Event findEventUniform(const Obstacle& obstacle, double from_half_angle_rad, int frozen,
                         const JointAngles& frozen_q, double end_half_angle_rad, double& clear_half_angle_rad) const;
  void backbone(const JointAngles& q, BackbonePoints& points) const;
  const FingerModel& model_;
  double length_m_ = 0.0;
  bool uniform_ = false;  ///< findEventUniform applies
};

/// The contact rule for one obstacle that stays where it is while the pressure changes (a grasp): the touch events
/// do not depend on the pressure asked for, so each is found once and kept. A pressure within what is already known
/// costs the free model and the backbone only; the answers are those of ContactSolver::solve, bit for bit. Not
/// thread-safe (it caches); one per finger and obstacle.
class ContactTracker {
 public:
  ContactTracker(const FingerModel& model, const Obstacle& obstacle);
  ContactState solve(double gauge_pa);
  /// The obstacle lies beyond the finger's length: solve() is the free model alone.
  bool outOfReach() const { return out_of_reach_; }

 private:
  ContactSolver solver_;
  Obstacle obstacle_;
  bool out_of_reach_ = false, overlaps_at_rest_ = false, failed_ = false;
  std::vector<ContactSolver::Event> events_;
  int frozen_ = 0;
  JointAngles frozen_q_;
  double clear_gauge_pa_ = 0.0;  // the pressure up to which no touch follows the last event
};

}  // namespace pneumatic_finger
