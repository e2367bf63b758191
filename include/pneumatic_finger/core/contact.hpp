// The finger closing on an object: a kinematic contact rule on top of the free model (docs/GRASP.md). ROS-free.
//
// In the finger's bending plane (x along the unbent finger from the mount, y toward the strain-limited side, where
// the backbone runs) an obstacle is a convex region. As the pressure rises from 0, every joint follows its free
// angle q_n(p) until the backbone O_0..O_{N+1} would enter the obstacle. At that first touch, at pressure p*, let
// segment m (O_m -> O_{m+1}, moved by joints 1..m) be the segment that touches: every still-free joint up to m
// freezes at its angle at p*. Later joints go on following q_n(p), and the rule repeats up to the pressure asked
// for. The force at the contacts is contactNormalForcesN's, computed only on request.
#pragma once

#include <Eigen/Core>

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/obstacle.hpp"

namespace pneumatic_finger {

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
    kBeyondLimitPoint,  ///< at or beyond the membrane law's limit point: no shape (the free finger at rest is given)
  };
  Status status = Status::kFree;
  JointAngles joint_angle_rad;         ///< q_1..q_N as the contact rule gives them (rad)
  BackbonePoints backbone_m;           ///< O_0..O_{N+1} (m)
  std::vector<bool> held;              ///< per joint: frozen by contact
  std::vector<Eigen::Vector2d> contact_points_m;  ///< where the backbone touches (one per touch event)
  std::vector<int> contact_segments;   ///< per contact point: the backbone segment touching (O_m -> O_{m+1}: m)
  JointAngles held_since_gauge_pa;     ///< per joint: the pressure of the touch that froze it (Pa; NaN: free)
  double first_touch_gauge_pa = std::numeric_limits<double>::quiet_NaN();  ///< p* of the first touch (NaN: none)
  int touches = 0;                     ///< touch events solved
};

/// One touch event of the contact rule: joints 1..frozen held at frozen_q from gauge_pa on.
struct TouchEvent {
  bool found = false, failed = false;
  double gauge_pa = 0.0;
  double search_x = 0.0;  ///< the search variable at the touch (contact.cpp)
  int frozen = 0;
  int segment = 0;  ///< the backbone segment that touches (O_segment -> O_segment+1)
  JointAngles frozen_q;
  Eigen::Vector2d point_m = Eigen::Vector2d::Zero();
};

/// The normal force (N) with which the finger presses at each of @p contact's contact points at @p gauge_pa
/// (docs/MODEL.md, "Force"; src/core/contact_force.cpp), into @p force_n (one per contact point; cleared first).
/// Each held joint exerts the moment of its walls held since its touch (FingerModel::heldJointMomentsNm); the moments
/// are shared by the joints' compliance so that no contact point moves along its normal, the normal of its backbone
/// segment; frictionless. A contact that would pull gets 0 and the others are solved again. Empty for a contact
/// state that is not in contact.
void contactNormalForcesN(const FingerModel& model, double gauge_pa, const ContactState& contact,
                          std::vector<double>& force_n);

/// The total normal force (N) of @p contact at @p gauge_pa: the sum of contactNormalForcesN (0 without contact).
double totalContactForceN(const FingerModel& model, double gauge_pa, const ContactState& contact);

/// The smallest gauge pressure (Pa) up to @p max_gauge_pa at which a finger closing on one object presses on it with
/// a total normal force of @p force_n, by bisection (the force does not fall as the pressure rises); @p contact_at
/// gives the contact state at a pressure (a ContactTracker's solve). false, with @p why, for a force that is not a
/// finite number > 0, or one that no pressure up to the limit gives (saying the most it gives).
bool gaugeForContactForce(const FingerModel& model, const std::function<ContactState(double)>& contact_at,
                          double force_n, double max_gauge_pa, double& gauge_pa, std::string& why);

/// The supplied volume (m^3) of the finger in @p contact at @p gauge_pa (docs/MODEL.md, "Volume", "With an object"):
/// each chamber's two walls take half its growth each; a wall at a held joint keeps the bulge its chamber had when
/// that joint was held (held_since_gauge_pa), every other wall has the free bulge at @p gauge_pa; plus the dead gas's
/// compression. Without contact it is FingerModel::suppliedVolumeAt. NaN at or beyond the limit point.
/// @p free_bulge_m: the free walls' bulges at @p gauge_pa when the caller has them (a FingerState's bulge_m, N
/// entries), else solved here.
double suppliedVolumeInContact(const FingerModel& model, const ContactState& contact, double gauge_pa,
                               const double* free_bulge_m = nullptr);

/// The finger closing on an object driven by volume: the gauge pressure (Pa) at which it has taken
/// @p supplied_volume_m3, where @p contact_at gives the contact state at a pressure (a ContactTracker's solve), up to
/// @p max_gauge_pa and below the limit point. false, with @p why, for a volume that is not a finite number >= 0, or
/// more than the finger takes there (saying how much it takes).
bool gaugeForVolumeInContact(const FingerModel& model, const std::function<ContactState(double)>& contact_at,
                             double supplied_volume_m3, double max_gauge_pa, double& gauge_pa, std::string& why);

/// Applies the contact rule to a model. Holds no state of its own: safe beside the model's other const users.
class ContactSolver {
 public:
  explicit ContactSolver(const FingerModel& model);

  /// The finger at @p gauge_pa with @p obstacle, found from scratch (ContactTracker keeps what it found).
  ContactState solve(double gauge_pa, const Obstacle& obstacle) const;

  /// The backbone O_0..O_{N+1} (eq 38) for the joint angles @p q (rad) into @p points (m).
  void backbone(const JointAngles& q, BackbonePoints& points) const;

 private:
  friend class ContactTracker;
  /// The first touch after the search variable @p from_x with joints 1..@p frozen held, searched up to @p end_x (a
  /// grid step past it at most). Not found: @p clear_x is how far the search went clear. The variable is the free
  /// walls' half angle for identical chambers with the robust solver, else sqrt(P) (src/core/touch_search.hpp).
  TouchEvent findEvent(const Obstacle& obstacle, double from_x, int frozen, const JointAngles& frozen_q, double end_x,
                       double& clear_x) const;
  /// The search variable at @p gauge_pa, where the free walls' half angle is @p free_half_angle_rad.
  double searchVariable(double gauge_pa, double free_half_angle_rad) const;
  /// The gauge pressure at the search variable @p x; false where none gives it.
  bool gaugeAt(double x, double& gauge_pa) const;
  const FingerModel& model_;
  double length_m_ = 0.0;
  bool uniform_ = false;  ///< the search runs in the half angle
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
  /// Finds the touch events after the last one known, up to @p pressure (or the first failure).
  void findEventsUpTo(double pressure, double free_half_angle_rad);
  /// Writes the events up to @p pressure into @p out; returns the count of held joints from the mount.
  int applyEventsUpTo(double pressure, ContactState& out) const;

  ContactSolver solver_;
  Obstacle obstacle_;
  bool out_of_reach_ = false, overlaps_at_rest_ = false, failed_ = false;
  std::vector<TouchEvent> events_;
  int frozen_ = 0;
  JointAngles frozen_q_;
  double clear_gauge_pa_ = 0.0;  // the pressure up to which no touch follows the last event
};

}  // namespace pneumatic_finger
