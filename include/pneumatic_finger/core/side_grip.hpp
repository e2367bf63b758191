// A part held by its side in a ring of identical fingers (docs/DESIGN.md, "A grip"): the lowest pressure at which the
// cell's grasp rule (hold_rule.hpp) says the grip holds it. What the design search's grip target asks of a drawing,
// before any gripper file names the fingers' mounts. ROS-free.
#pragma once

#include <limits>
#include <string>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/hold_rule.hpp"
#include "pneumatic_finger/core/obstacle.hpp"

namespace pneumatic_finger {

/// A cylindrical part on the gripper's axis, held by its side, and the gripper: its fingers on a ring around the axis,
/// each pointing along it with its strain-limited side facing it (config/gripper.yaml's layout). The defaults are
/// the shipped gripper's and the cell's.
struct SideGripTask {
  double mass_kg = 0.0;                 ///< the part's mass (kg), > 0
  double diameter_m = 0.0;              ///< the part's diameter (m), > 0 and < 2 mount_radius_m
  double lift_acceleration_mps2 = 0.0;  ///< the lift's peak upward acceleration (m/s^2), >= 0
  int finger_count = 3;                 ///< fingers on the ring, >= 1
  double mount_radius_m = 0.035;        ///< from the gripper's axis to each finger's base (m)
  double friction_coefficient = kDefaultFrictionCoefficient;
  double hold_margin = kDefaultHoldMargin;
  /// The grip must hold at or below this share of the walls' limit point, past which the chambers balloon and let go:
  /// a cast part's scatter in modulus or wall (a few percent) must not carry it there. In (0, 1].
  double limit_share = 0.9;
  /// The highest gauge pressure the grip may use (Pa; the design search takes the base file's max_gauge_pa).
  double max_gauge_pa = std::numeric_limits<double>::quiet_NaN();
};

/// "KEY=VALUE,..." with mass_kg and diameter_m, and optionally lift_mps2, fingers, mount_radius_m, friction, margin,
/// limit_share.
/// @throws ParameterError naming the key or value that is wrong and what is expected
SideGripTask parseSideGripTask(const std::string& text);

/// @throws ParameterError for a part or gripper outside its ranges (SideGripTask's; max_gauge_pa aside), naming it
void checkSideGripTask(const SideGripTask& task);

/// The part's side in a finger's plane: the strip between mount_radius_m - radius and mount_radius_m + radius on the
/// finger's bending side (+y), along the whole finger and past both its ends (the side is taken as long as the
/// finger can reach: no rim is touched).
Obstacle partSideInFingerPlane(const FingerModel& model, const SideGripTask& task);

/// The lowest gauge pressure (Pa) up to task.max_gauge_pa and limit_share x the walls' limit point at which each
/// finger presses on the part's side with the normal force the grasp rule asks of it (requiredFingerForceN); NaN,
/// with @p why, where none does.
/// @throws ParameterError as checkSideGripTask, and for a max_gauge_pa that is not a pressure > 0
double holdingGaugePa(const FingerModel& model, const SideGripTask& task, std::string* why = nullptr);

}  // namespace pneumatic_finger
