#include "pneumatic_finger/core/pressure_input.hpp"

#include <cmath>
#include <cstdio>

#include "pneumatic_finger/core/parameters.hpp"

namespace pneumatic_finger {

namespace {

std::string seconds(double t) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6f", t);
  return b;
}

}  // namespace

PressureInputPolicy::PressureInputPolicy(const PressureInputSettings& settings) : settings_(settings) {}

void PressureInputPolicy::problem(const std::string& what, double now_s) {
  have_problem_ = true;
  last_problem_s_ = now_s;
  last_problem_ = what;
}

void PressureInputPolicy::startTimeline(double receive_s) {
  // Everything that compares times forgets the old timeline; the counters stay.
  ++counters_.time_jumps;
  have_accepted_ = false;
  recent_.clear();
  if (have_problem_ && last_problem_s_ > receive_s) have_problem_ = false;
}

InputDecision PressureInputPolicy::onMessage(double absolute_pa, double stamp_s, double receive_s) {
  InputDecision d;
  if (receiveOrThrottle(receive_s, d)) return d;
  if (refuseValue(absolute_pa, receive_s, d)) return d;
  bool replaced = false;
  const double stamp = stampOf(stamp_s, receive_s, replaced, d);
  if (refuseStamp(stamp, replaced, receive_s, d)) return d;
  accept(absolute_pa, stamp, replaced, receive_s, d);
  return d;
}

// Every message, pressure or volume: counted, the clock's jumps noted, and one that comes sooner than the rate cap
// allows after the last accepted one throttled (true: decided).
bool PressureInputPolicy::receiveOrThrottle(double receive_s, InputDecision& d) {
  ++counters_.received;
  noteReceived(receive_s, d);
  if (settings_.max_rate_hz > 0 && have_accepted_ && receive_s - last_accepted_s_ < 1.0 / settings_.max_rate_hz) {
    ++counters_.throttled;
    d.verdict = InputVerdict::kThrottled;
    return true;
  }
  return false;
}

// The clock itself went back (a bag played with --clock --loop, a simulation reset): a new timeline, as
// robot_state_publisher treats it. Said once, by the caller, from time_jumped. And the input rate's window.
void PressureInputPolicy::noteReceived(double receive_s, InputDecision& d) {
  if (have_received_ && receive_s < last_received_s_) {
    startTimeline(receive_s);
    d.time_jumped = true;
    d.problem = "the clock jumped back from " + seconds(last_received_s_) + " s to " + seconds(receive_s) +
                " s: continuing on the new time";
  }
  have_received_ = true;
  last_received_s_ = receive_s;
  recent_.push_back(receive_s);
  while (!recent_.empty() && receive_s - recent_.front() > 1.0) recent_.pop_front();
}

// Bad values are refused; the last valid state stays (nothing is published). true: refused.
bool PressureInputPolicy::refuseValue(double absolute_pa, double receive_s, InputDecision& d) {
  if (!std::isfinite(absolute_pa)) {
    ++counters_.refused_not_finite;
    d.verdict = InputVerdict::kRefusedNotFinite;
    d.problem = notFinitePressureMessage(absolute_pa);
  } else if (absolute_pa < 0) {
    ++counters_.refused_negative_absolute;
    d.verdict = InputVerdict::kRefusedNegativeAbsolute;
    d.problem = negativeAbsoluteMessage(absolute_pa);
  } else {
    return false;
  }
  problem(d.problem, receive_s);
  return true;
}

// The stamp to publish with. Zero (what `rostopic pub` and many drivers send): the receive time, counted, not a
// problem. Far from the receive time (a regulator whose clock is wrong): the receive time, and a problem worth
// reporting.
double PressureInputPolicy::stampOf(double stamp_s, double receive_s, bool& replaced, InputDecision& d) {
  replaced = false;
  if (stamp_s == 0.0) {
    ++counters_.zero_stamps;
    replaced = true;
    return receive_s;
  }
  if (std::fabs(stamp_s - receive_s) > settings_.stamp_tolerance_s) {
    ++counters_.far_stamps;
    d.problem = "stamp " + seconds(stamp_s) + " s replaced by the receive time";
    problem(d.problem, receive_s);
    replaced = true;
    return receive_s;
  }
  return stamp_s;
}

// A stamp not newer than the last published one. true: refused (or dropped as the same instant).
bool PressureInputPolicy::refuseStamp(double stamp, bool replaced, double receive_s, InputDecision& d) {
  if (!have_accepted_ || stamp > last_stamp_s_) return false;
  if (replaced) {
    // Two messages within one tick of the clock (simulated time advances in steps): the same instant, which tf must
    // not see twice. Not the sender's fault: dropped like a throttled one; the next tick takes the newest.
    ++counters_.throttled;
    d.verdict = InputVerdict::kThrottled;
    return true;
  }
  if (last_stamp_s_ - stamp > settings_.time_jump_s) {
    // The stamps went back by more than any reordering: a new timeline (a bag replayed without --clock).
    startTimeline(receive_s);
    d.time_jumped = true;
    d.problem = "the stamps jumped back from " + seconds(last_stamp_s_) + " s to " + seconds(stamp) +
                " s: continuing on the new time";
    return false;
  }
  // Within the same timeline: tf and the planners downstream must never see time run backwards.
  ++counters_.refused_out_of_order;
  d.verdict = InputVerdict::kRefusedOutOfOrder;
  d.problem = "stamp " + seconds(stamp) + " s is not newer than the last published " + seconds(last_stamp_s_) + " s";
  problem(d.problem, receive_s);
  return true;
}

// An accepted pressure: its gauge value, flagged above the validated range, clamped above the model's.
void PressureInputPolicy::accept(double absolute_pa, double stamp, bool replaced, double receive_s, InputDecision& d) {
  ++counters_.accepted;
  have_accepted_ = true;
  last_accepted_s_ = receive_s;
  last_stamp_s_ = stamp;
  d.verdict = InputVerdict::kAccept;
  d.stamp_s = stamp;
  d.stamp_replaced = replaced;
  const double gauge = absolute_pa - settings_.atmospheric_pa;
  last_gauge_pa_ = gauge;
  // The model's range, as every interface applies it (pressure_range.hpp): above it, a glitching regulator or a
  // finger driven past its rating gets the finger at the top of the range, where the URDF's joint limits are.
  const PressureRange range = this->range();
  const RangeCheck check = checkGaugeRange(gauge, range);
  d.out_of_range = check.above_validated;
  if (d.out_of_range) ++counters_.out_of_range;
  if (check.clamped) {
    ++counters_.clamped;
    d.clamped = true;
    d.problem = clampedMessage(gauge, range);
    problem(d.problem, receive_s);
  }
  d.gauge_pa = check.gauge_pa;
}

InputDecision PressureInputPolicy::onVolumeMessage(double volume_m3, double receive_s) {
  InputDecision d;
  if (receiveOrThrottle(receive_s, d)) return d;
  if (!std::isfinite(volume_m3)) {
    ++counters_.refused_not_finite;
    d.verdict = InputVerdict::kRefusedNotFinite;
    d.problem = notFiniteVolumeMessage(volume_m3);
    problem(d.problem, receive_s);
    return d;
  }
  ++counters_.accepted;
  have_accepted_ = true;
  last_accepted_s_ = last_stamp_s_ = receive_s;
  d.verdict = InputVerdict::kAccept;
  d.stamp_s = receive_s;
  d.stamp_replaced = true;
  return d;
}

void PressureInputPolicy::noteVolumeNotFollowed(const std::string& what, double now_s) {
  ++counters_.beyond_limit_point;
  problem(what, now_s);
}

void PressureInputPolicy::noteVolumeClamped(const std::string& what, double now_s) {
  ++counters_.clamped;
  problem(what, now_s);
}

void PressureInputPolicy::noteVacuum(double gauge_pa, double now_s) {
  ++counters_.vacuum;
  problem(vacuumMessage(gauge_pa) + " is published", now_s);
}

void PressureInputPolicy::noteSolverFailure(const std::string& what, double now_s) {
  ++counters_.solver_failures;
  problem(what, now_s);
}

void PressureInputPolicy::noteBeyondLimitPoint(double gauge_pa, double limit_gauge_pa, double now_s) {
  ++counters_.beyond_limit_point;
  problem("gauge pressure " + formatMessage(gauge_pa) + " Pa is at or beyond the membrane wall's limit point " +
              formatMessage(limit_gauge_pa) + " Pa, where the pressure does not determine the shape: the wall has no far "
              "branch to snap to and balloons without bound (a risk of bursting); last state kept",
          now_s);
}

InputReport PressureInputPolicy::report(double now_s) {
  InputReport r;
  while (!recent_.empty() && now_s - recent_.front() > 1.0) recent_.pop_front();
  r.rate_hz = static_cast<double>(recent_.size());
  r.age_s = have_received_ ? now_s - last_received_s_ : -1.0;
  const bool recent_problem = have_problem_ && now_s - last_problem_s_ <= kProblemHoldS && now_s >= last_problem_s_;
  const char* input = settings_.volume_input ? "supplied volume" : "pressure";
  if (!have_received_) {
    r.level = InputHealth::kWarn;
    r.message = std::string("no ") + input + " received yet";
  } else if (r.age_s > settings_.stale_timeout_s) {
    r.level = InputHealth::kError;
    char b[96];
    std::snprintf(b, sizeof b, "stale: no %s for %.1f s; last state kept", input, r.age_s);
    r.message = b;
  } else if (recent_problem) {
    r.level = InputHealth::kWarn;
    r.message = last_problem_;
  } else if (last_gauge_pa_ > settings_.validated_max_gauge_pa) {
    r.level = InputHealth::kWarn;
    r.message = aboveValidatedMessage(last_gauge_pa_, range());
  } else {
    r.level = InputHealth::kOk;
    r.message = settings_.volume_input && past_limit_point_
                    ? "ok: past the wall's limit point, which volume control follows (the pressure falls as the "
                      "volume grows)"
                    : "ok";
  }
  return r;
}

}  // namespace pneumatic_finger
