// The rules for the regulator's pressure messages, decided once, without ROS: which messages are taken, with which
// stamp and which gauge pressure, which are refused and why, when the clock has jumped back, and what the
// diagnostics say. Times are seconds on the node's clock (ROS time: wall or simulated); a unit test drives this class
// with synthetic times, and the node only forwards messages to it and publishes its verdicts.
#pragma once

#include <deque>
#include <string>

#include "pneumatic_finger/core/pressure_range.hpp"
#include "pneumatic_finger/core/units.hpp"

namespace pneumatic_finger {

/// The node's input settings (their defaults and ranges are defined once, with the node's other parameters).
struct PressureInputSettings {
  double atmospheric_pa = kStandardAtmospherePa;      ///< P_o: gauge = absolute - P_o (Pa)
  double max_gauge_pa = kModelMaxGaugePa;        ///< gauge pressures above this are clamped to it (Pa)
  double validated_max_gauge_pa = kValidatedMaxGaugePa;  ///< top of the calibrated range (Pa); above it the twin extrapolates
  double max_rate_hz = 0.0;              ///< model cycles per second at most; 0: every message
  double stamp_tolerance_s = 1.0;        ///< a stamp further than this from the receive time is replaced by it (s)
  double time_jump_s = 1.0;              ///< a stamp older than the last by more than this starts a new timeline (s)
  double stale_timeout_s = 1.0;          ///< no message for longer than this: the input is stale (s)
  bool volume_input = false;             ///< the input is a supplied volume (~volume_topic): the reports name it so
};

/// What happens to one message.
enum class InputVerdict {
  kAccept,                   ///< evaluate gauge_pa and publish with stamp_s
  kThrottled,                ///< dropped: within 1/max_rate_hz of the last accepted one (not a problem)
  kRefusedNotFinite,         ///< NaN or infinite pressure: refused, the last state stays
  kRefusedNegativeAbsolute,  ///< absolute pressure < 0: refused
  kRefusedOutOfOrder,        ///< stamp not newer than the last accepted one, within the same timeline: refused
};

/// The decision on one message.
struct InputDecision {
  InputVerdict verdict = InputVerdict::kAccept;
  double gauge_pa = 0.0;     ///< the pressure to evaluate (clamped to max_gauge_pa); negative: a vacuum
  double stamp_s = 0.0;      ///< the stamp to publish with
  bool stamp_replaced = false;  ///< stamp_s is the receive time (else it is the message's own stamp, unchanged)
  bool clamped = false;      ///< gauge was above max_gauge_pa
  bool out_of_range = false; ///< gauge is above validated_max_gauge_pa
  bool time_jumped = false;  ///< this message starts a new timeline (the clock or the stamps went back)
  std::string problem;       ///< what was wrong or corrected, for the log; empty when nothing was
};

/// Running counts, for diagnostics.
struct InputCounters {
  long received = 0, accepted = 0, throttled = 0;
  long refused_not_finite = 0, refused_negative_absolute = 0, refused_out_of_order = 0;
  long zero_stamps = 0;       ///< zero stamps replaced by the receive time (what `rostopic pub` sends: normal)
  long far_stamps = 0;        ///< stamps far from the receive time, replaced by it (a regulator with a wrong clock)
  long time_jumps = 0;        ///< new timelines (a looping bag, a simulation reset)
  long vacuum = 0, clamped = 0, out_of_range = 0;
  long solver_failures = 0;   ///< accepted messages whose evaluation the solver could not finish (nothing published)
  long beyond_limit_point = 0;  ///< accepted messages at or beyond the membrane wall's limit point (no shape published)
};

/// Diagnostics levels, as diagnostic_msgs defines them.
enum class InputHealth { kOk = 0, kWarn = 1, kError = 2 };

struct InputReport {
  InputHealth level = InputHealth::kOk;
  std::string message;
  double rate_hz = 0.0;       ///< messages received in the last second
  double age_s = -1.0;        ///< seconds since the last message (-1: none yet)
};

class PressureInputPolicy {
 public:
  explicit PressureInputPolicy(const PressureInputSettings& settings);

  /// Decides on one message.
  /// @param[in] absolute_pa the message's fluid_pressure (Pa, absolute)
  /// @param[in] stamp_s its header stamp (s; 0: none)
  /// @param[in] receive_s the node's clock when it arrived (s)
  InputDecision onMessage(double absolute_pa, double stamp_s, double receive_s);

  /// Volume as the input (finger_node's ~volume_topic; docs/MODEL.md "Volume"): a supplied volume (m^3) received at
  /// @p receive_s, under the same rate, throttle and staleness rules as a pressure. It carries no stamp: the receive
  /// time is its stamp (stamp_replaced). Refused: not finite. The range rule does not apply: the pressure is the
  /// model's answer (noteGaugeFromVolume).
  InputDecision onVolumeMessage(double volume_m3, double receive_s);

  /// The pressure the model gave an accepted volume: diagnostics' last gauge pressure. @p past_limit_point: the volume
  /// lies past the pressure's limit point, where volume control follows the wall and the pressure falls (the report
  /// says so while it lasts).
  void noteGaugeFromVolume(double gauge_pa, bool past_limit_point) {
    last_gauge_pa_ = gauge_pa;
    past_limit_point_ = past_limit_point;
  }

  /// A supplied volume the model does not follow (above its volume limit): counted with the limit point's, the last
  /// state kept, @p what reported.
  void noteVolumeNotFollowed(const std::string& what, double now_s);

  /// A supplied volume above the one that makes max_gauge_pa (maxSuppliedVolumeM3): counted with the clamped
  /// pressures, @p what reported.
  void noteVolumeClamped(const std::string& what, double now_s);

  /// The model's answer to an accepted message was a vacuum (gauge < 0): counted and reported.
  void noteVacuum(double gauge_pa, double now_s);

  /// A solver failure on an accepted message (non-finite result): counted as a problem, nothing published.
  void noteSolverFailure(const std::string& what, double now_s);
  /// A pressure at or beyond the membrane wall's limit point @p limit_gauge_pa: no shape, the last one kept.
  void noteBeyondLimitPoint(double gauge_pa, double limit_gauge_pa, double now_s);

  /// The diagnostics report at @p now_s: ERROR when stale, WARN while a refusal or correction is recent (5 s) or
  /// before the first message, OK otherwise. A zero stamp is not a problem.
  InputReport report(double now_s);

  /// New settings (a live reconfiguration); the counters and the timeline stay.
  void updateSettings(const PressureInputSettings& settings) { settings_ = settings; }

  const InputCounters& counters() const { return counters_; }
  const PressureInputSettings& settings() const { return settings_; }
  /// The model's range these settings give (pressure_range.hpp): the rule and the words every interface shares.
  PressureRange range() const { return {settings_.max_gauge_pa, settings_.validated_max_gauge_pa}; }
  double lastGaugePa() const { return last_gauge_pa_; }
  /// The most recent refusal or correction (empty before any).
  const std::string& lastProblem() const { return last_problem_; }

  /// How long a refusal or correction stays on the report: longer than any diagnostics period, so that a single
  /// bad message is seen by whoever watches.
  static constexpr double kProblemHoldS = 5.0;

 private:
  void problem(const std::string& what, double now_s);
  void startTimeline(double receive_s);
  // onMessage's steps, in order (pressure_input.cpp).
  bool receiveOrThrottle(double receive_s, InputDecision& d);
  void noteReceived(double receive_s, InputDecision& d);
  bool refuseValue(double absolute_pa, double receive_s, InputDecision& d);
  double stampOf(double stamp_s, double receive_s, bool& replaced, InputDecision& d);
  bool refuseStamp(double stamp, bool replaced, double receive_s, InputDecision& d);
  void accept(double absolute_pa, double stamp, bool replaced, double receive_s, InputDecision& d);

  PressureInputSettings settings_;
  InputCounters counters_;
  std::deque<double> recent_;      // receive times within the last second
  bool have_accepted_ = false, have_received_ = false;
  double last_stamp_s_ = 0.0;      // stamp of the last accepted message
  double last_accepted_s_ = 0.0;   // receive time of the last accepted message (throttling)
  double last_received_s_ = 0.0;
  double last_problem_s_ = 0.0;
  bool have_problem_ = false;
  std::string last_problem_;
  double last_gauge_pa_ = 0.0;
  bool past_limit_point_ = false;  // the last accepted volume lies past the pressure's limit point
};

}  // namespace pneumatic_finger
