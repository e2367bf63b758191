// The model's pressure range: one rule, one status and one set of words for every interface (finger_node,
// finger_model, Python's evaluate). FingerModel itself answers any pressure; an interface applies this rule first,
// so that a regulator's glitch, a typo or a sweep past the finger's rating gives the same answer everywhere.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "pneumatic_finger/core/evaluation.hpp"
#include "pneumatic_finger/core/units.hpp"

namespace pneumatic_finger {

class FingerModel;

/// Where the model holds (Pa gauge).
struct PressureRange {
  /// Above it the finger at max_gauge_pa is given, status kClamped: the URDF's joint limits are there, and the walls
  /// would otherwise curl toward pi/2 each (the paper law) with no finger to show it.
  double max_gauge_pa = kModelMaxGaugePa;
  /// The top of the calibrated range: up to max_gauge_pa the twin extrapolates, and says so.
  double validated_max_gauge_pa = kValidatedMaxGaugePa;

  /// The range up to @p max_gauge_pa (an interface's --max-gauge-pa or max_gauge_pa=), the validated range no higher.
  /// @throws ParameterError naming the value unless it is finite and > 0
  static PressureRange upTo(double max_gauge_pa);

  /// This range with its top replaced by @p max_gauge_pa (a tool's --max-gauge-pa, Python's max_gauge_pa=): the
  /// validated range kept, no higher than the new top. @throws ParameterError as upTo
  PressureRange withTop(double max_gauge_pa) const;
};

/// One pressure against the range.
struct RangeCheck {
  double gauge_pa = 0.0;         ///< what to evaluate: the pressure, or max_gauge_pa above it
  bool clamped = false;          ///< it was above max_gauge_pa
  bool above_validated = false;  ///< it was above validated_max_gauge_pa (and so, too, when clamped)
};

/// @p gauge_pa against @p range (NaN and inf pass unchanged: the model refuses them with its own status).
RangeCheck checkGaugeRange(double gauge_pa, const PressureRange& range);

/// The same rule for a pressure an input policy has already checked (finger_node's: a supplied volume clamped to its
/// range is a clamped pressure): @p gauge_pa as evaluated, @p clamped as the policy found it, and above the validated
/// range where clamped or above @p validated_max_gauge_pa.
RangeCheck checkedInput(double gauge_pa, bool clamped, double validated_max_gauge_pa);

/// The words every interface says (its log, stderr, diagnostics), with numbers in formatMessage's format.
std::string clampedMessage(double gauge_pa, const PressureRange& range);
std::string vacuumMessage(double gauge_pa);
/// A gauge pressure below -atmospheric_pressure_pa is a negative absolute pressure, which no input can be (a sensor's
/// fault, a typo): refused by every interface in these words (finger_node keeps its last state).
std::string negativeAbsoluteMessage(double absolute_pa);
/// @throws ParameterError in negativeAbsoluteMessage's words when @p gauge_pa + @p atmospheric_pa < 0
void refuseNegativeAbsolute(double gauge_pa, double atmospheric_pa);
/// A pressure or a supplied volume that is not a number: refused (no shape), in the same words everywhere.
std::string notFinitePressureMessage(double pa);
std::string notFiniteVolumeMessage(double supplied_volume_m3);
std::string aboveValidatedMessage(double gauge_pa, const PressureRange& range);

/// A batch's pressures through the rule: @p out[i] = checkGaugeRange(in[i]).gauge_pa. Returns how many were clamped
/// (0: @p out equals @p in). @p in and @p out may be the same array.
std::size_t clampToRange(const double* in, double* out, std::size_t count, const PressureRange& range);

/// The same rule for the volume input (one input domain for pressure and volume): the most a supply may push in is
/// the volume that makes max_gauge_pa along the inflation, and a larger volume gives the finger at that volume, status kClamped, with
/// volumeClampedMessage's words. Below the pressure's limit point that is suppliedVolumeAt(max_gauge_pa); with the
/// limit point within the range, the volume past it where the far branch's pressure climbs back to max_gauge_pa; +inf
/// where the pressure never gets there (a Neo-Hookean balloon: volumeLimitM3() and the backbone's self-contact bound
/// it). Computed once per model and range (a few hundred volume solves at most): the interfaces keep it.
double maxSuppliedVolumeM3(const FingerModel& model, const PressureRange& range);

/// One volume against its top (NaN and inf pass unchanged: the model refuses them with its own status; a negative
/// volume passes too: the model's vacuum).
struct VolumeCheck {
  double volume_m3 = 0.0;  ///< what to evaluate: the volume, or the top above it
  bool clamped = false;    ///< it was above the top
};
VolumeCheck checkVolumeRange(double supplied_volume_m3, double max_supplied_volume_m3);

/// The words every interface says for a volume the model does not follow: past @p volume_limit_m3 (the gas in the
/// drive snaps the finger there, or the wall locks), or one the solver found no finite answer for.
std::string volumeNotFollowedMessage(double supplied_volume_m3, bool solver_failure, double volume_limit_m3);

/// The words every interface says for a clamped volume.
std::string volumeClampedMessage(double supplied_volume_m3, double max_supplied_volume_m3, const PressureRange& range);

/// A batch of volumes through the rule, as clampToRange: returns how many were clamped.
std::size_t clampVolumesToRange(const double* in, double* out, std::size_t count, double max_supplied_volume_m3);

}  // namespace pneumatic_finger
