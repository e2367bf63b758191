// What pressure a gripper command needs: the planning half of the gripper action, ROS-free (the server only
// gathers the fingers' answers and forwards the plan to the regulator). docs/GRASP.md.
#pragma once

#include <string>
#include <vector>

#include "pneumatic_finger/core/units.hpp"

namespace pneumatic_finger {

/// What a grasp adds beyond the last finger's touch unless told otherwise (Pa): 0.1 kg/cm^2 (the gripper action's
/// squeeze_margin_pa).
constexpr double kDefaultSqueezeMarginPa = 0.1 * kPaPerKgfPerCm2;

/// One finger's answers for a goal.
struct FingerGoalAnswer {
  std::string name;      ///< for messages ("finger_a")
  double free_gauge_pa;  ///< gauge pressure at which the free finger's tip angle reaches the goal; NaN: none in range
  double touch_gauge_pa; ///< predicted first touch of the grasp object (Pa gauge); NaN: no object, or never in range
};

struct GripperPlan {
  enum class Kind {
    kGrasp,        ///< every finger touches the object before the goal: its touch pressure plus the margin
    kClose,        ///< the goal position, free (the object, if any, is not touched by every finger first)
    kUnreachable,  ///< no pressure up to the limit does either: abort, command nothing
  };
  Kind kind = Kind::kUnreachable;
  double gauge_pa = 0.0;  ///< what to command (Pa gauge), for kGrasp and kClose
  std::string message;    ///< what was decided and why, naming the finger that decides it
};

/// Plans a gripper command. @p limit_pa is the highest gauge pressure allowed (the goal's max_effort, or the
/// fingers' range), @p squeeze_margin_pa what a grasp adds beyond the last finger's touch (the result is capped at
/// the limit). free_gauge_pa and touch_gauge_pa above the limit count as not in range.
GripperPlan planGripperCommand(const std::vector<FingerGoalAnswer>& fingers, double goal_position_rad,
                               double limit_pa, double squeeze_margin_pa, bool object_present);

}  // namespace pneumatic_finger
