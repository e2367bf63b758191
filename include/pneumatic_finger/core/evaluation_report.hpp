// What every interface reports for one evaluation: one outcome code (EvaluationStatus, as today's subscribers read it)
// and the flags that can hold at once beside it. One rule, here, for finger_node's finger_state, Python's evaluate()
// and finger_model's --status columns, so that a clamped, snapped, self-crossing pressure above the validated range
// reads the same everywhere and loses none of the four.
#pragma once

#include <cstdint>
#include <string>

#include "pneumatic_finger/core/evaluation.hpp"
#include "pneumatic_finger/core/pressure_range.hpp"

namespace pneumatic_finger {

/// What happened besides the outcome; any number at once. FingerModelState's FLAG_* and Python's pf.STATUS_FLAGS are
/// these bits (tests hold them to it). New flags take the next bit.
enum StatusFlag : std::uint8_t {
  kFlagClamped = 1,       ///< the input was above max_gauge_pa (or the volume that makes it): the finger there is given
  kFlagFarBranch = 2,     ///< some wall is on its far branch, past a snap-through: the shape depends on the path
  kFlagMeetsItself = 4,   ///< the backbone crosses itself (self_contact.hpp): the model passes through the finger
  kFlagExtrapolated = 8,  ///< above validated_max_gauge_pa (a file no actuator validates: every pressure above 0)
};
inline constexpr int kStatusFlagCount = 4;

/// "clamped", "far branch", "meets itself", "extrapolated" for bit 0..3.
const char* statusFlagName(int bit);

/// The names of the flags set in @p flags, joined by ", "; "none" for 0.
std::string statusFlagNames(std::uint8_t flags);

/// One evaluation as every interface reports it.
struct EvaluationReport {
  EvaluationStatus status = EvaluationStatus::kOk;  ///< the outcome code as FingerModelState.status has carried it
  std::uint8_t flags = 0;                           ///< StatusFlag bits
};

/// The one rule. @p model_status is what FingerModel said (at the clamped pressure when @p range clamped it),
/// @p meets_itself whether the backbone it gave crosses itself. The status keeps its old precedence, so that
/// today's subscribers read what they read: a refusal (vacuum, not finite, solver failure, beyond the limit point)
/// first, then meets itself, then clamped, then the model's own; the flags keep everything the status hides.
EvaluationReport reportEvaluation(EvaluationStatus model_status, const RangeCheck& range, bool meets_itself);

}  // namespace pneumatic_finger
