// Where the finger meets itself (docs/MODEL.md, "Where the finger meets itself"): a bend so deep that the backbone
// O_0..O_{N+1} crosses or touches itself. The model has no self-contact, so past that point its shape passes through
// the finger; every interface says so with status kMeetsItself and selfContactMessage's words, as it says kClamped.
#pragma once

#include <Eigen/Core>

#include <string>

#include "pneumatic_finger/core/parameters.hpp"

namespace pneumatic_finger {

/// Whether the backbone @p backbone_m (O_0..O_{N+1} as columns, m) crosses or touches itself: two of its segments that
/// share no end point meet. A chain whose joints @p joint_angle_rad (N entries) turn by pi or less in all cannot close
/// a loop (a loop turns by more than pi before it meets itself), so it is answered without a segment test.
bool backboneMeetsItself(const Eigen::Ref<const Eigen::Matrix2Xd>& backbone_m, const double* joint_angle_rad);

/// The same from joint angles alone, the backbone built from @p parameters' segment lengths (eq 38).
bool jointsMeetThemselves(const FingerParameters& parameters, const double* joint_angle_rad);

/// The words every interface says, with the tip angle that got there.
std::string selfContactMessage(double tip_angle_rad);

}  // namespace pneumatic_finger
