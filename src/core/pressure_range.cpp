// The model's pressure range (pressure_range.hpp).
#include "pneumatic_finger/core/pressure_range.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/parameters.hpp"

namespace pneumatic_finger {

PressureRange PressureRange::upTo(double max_gauge_pa) {
  if (!(max_gauge_pa > 0) || std::isinf(max_gauge_pa)) {
    throw ParameterError("max_gauge_pa = " + formatMessage(max_gauge_pa) + " Pa must be finite and > 0");
  }
  PressureRange range;
  range.max_gauge_pa = max_gauge_pa;
  range.validated_max_gauge_pa = std::min(range.validated_max_gauge_pa, max_gauge_pa);
  return range;
}

PressureRange PressureRange::withTop(double max_gauge_pa) const {
  PressureRange range = upTo(max_gauge_pa);
  range.validated_max_gauge_pa = std::min(validated_max_gauge_pa, range.max_gauge_pa);
  return range;
}

RangeCheck checkGaugeRange(double gauge_pa, const PressureRange& range) {
  // +inf is not a pressure: the model refuses it. The validated range lies within the model's (upTo, withTop).
  const bool clamped = gauge_pa > range.max_gauge_pa && std::isfinite(gauge_pa);
  return checkedInput(clamped ? range.max_gauge_pa : gauge_pa, clamped, range.validated_max_gauge_pa);
}

RangeCheck checkedInput(double gauge_pa, bool clamped, double validated_max_gauge_pa) {
  RangeCheck c;
  c.gauge_pa = gauge_pa;
  c.clamped = clamped;
  c.above_validated = clamped || gauge_pa > validated_max_gauge_pa;
  return c;
}

std::string clampedMessage(double gauge_pa, const PressureRange& range) {
  return "gauge pressure " + formatMessage(gauge_pa) + " Pa is above max_gauge_pa " +
         formatMessage(range.max_gauge_pa) + " Pa, the top of the model's range: clamped to it";
}

std::string vacuumMessage(double gauge_pa) {
  return "gauge pressure " + formatMessage(gauge_pa) + " Pa is a vacuum, outside the model: the straight finger";
}

std::string negativeAbsoluteMessage(double absolute_pa) {
  return "absolute pressure " + formatMessage(absolute_pa) + " Pa is negative";
}

void refuseNegativeAbsolute(double gauge_pa, double atmospheric_pa) {
  if (gauge_pa + atmospheric_pa < 0.0) throw ParameterError(negativeAbsoluteMessage(gauge_pa + atmospheric_pa));
}

std::string notFinitePressureMessage(double pa) { return "pressure " + formatMessage(pa) + " Pa is not finite"; }

std::string notFiniteVolumeMessage(double supplied_volume_m3) {
  return "supplied volume " + formatMessage(supplied_volume_m3) + " m^3 is not finite";
}

std::string aboveValidatedMessage(double gauge_pa, const PressureRange& range) {
  if (range.validated_max_gauge_pa == 0.0) {
    return "gauge pressure " + formatMessage(gauge_pa) + " Pa: no actuator's data validate this file "
           "(validated_max_gauge_pa 0: a drawing or a coupon), so the twin's answer is a zero-shot prediction";
  }
  return "gauge pressure " + formatMessage(gauge_pa) + " Pa is above the validated range (0 to " +
         formatMessage(range.validated_max_gauge_pa) + " Pa): the twin extrapolates";
}

std::size_t clampToRange(const double* in, double* out, std::size_t count, const PressureRange& range) {
  // A volume's top is the pressure's rule with another number: one loop for both (clampVolumesToRange).
  return clampVolumesToRange(in, out, count, range.max_gauge_pa);
}

namespace {

// The pressure a volume makes, or NaN where the model does not follow it.
double gaugeOfVolume(const FingerModel& model, FingerWorkspace& ws, double v) {
  const FingerState& s = model.evaluateVolume(v, ws);
  const bool answered = s.status == EvaluationStatus::kOk || s.status == EvaluationStatus::kSnappedThrough;
  return answered ? s.gauge_pa : std::numeric_limits<double>::quiet_NaN();
}

// Between a followed volume @p lo (its pressure at most the top) and @p hi, which the model does not follow: where a
// Gent wall locks, its pressure climbs without bound before the lock, so the top is crossed in between (the volume
// there is returned); where the drive's gas snaps the finger first, it is not (+inf: the limit's own rule applies).
double crossingBeforeVolumeLimit(const FingerModel& model, FingerWorkspace& ws, double lo, double hi, double top_pa) {
  bool crossed = false;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double p = gaugeOfVolume(model, ws, mid);
    const bool above = std::isnan(p) || p > top_pa;  // NaN: past the limit, which lies above the crossing if any
    crossed = crossed || (above && !std::isnan(p));
    (above ? hi : lo) = mid;
  }
  return crossed ? lo : std::numeric_limits<double>::infinity();
}

}  // namespace

double maxSuppliedVolumeM3(const FingerModel& model, const PressureRange& range) {
  const double top_pa = range.max_gauge_pa;
  if (!(model.limitGaugePa() <= top_pa)) {  // no limit point in the range: the pressure rises with the volume
    const double v = model.suppliedVolumeAt(top_pa);
    return std::isfinite(v) ? std::min(v, model.volumeLimitM3()) : std::numeric_limits<double>::infinity();
  }
  // Past the limit point the pressure falls, then (a Gent wall's far branch) climbs again: find where it passes the
  // top, by growing steps from the limit point's volume, then halving the last step.
  FingerWorkspace ws(model);
  const double cap = std::min(model.volumeLimitM3(), 1e3 * model.limitPointVolumeM3());
  double lo = model.limitPointVolumeM3(), hi = lo;
  bool crossed = false;
  while (!crossed && hi < cap) {
    lo = hi;
    hi = std::min(cap, hi * 1.25);
    const double p = gaugeOfVolume(model, ws, hi);
    if (std::isnan(p)) return crossingBeforeVolumeLimit(model, ws, lo, hi, top_pa);  // no longer followed
    crossed = p > top_pa;
  }
  if (!crossed) return std::numeric_limits<double>::infinity();
  for (int i = 0; i < 80 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (gaugeOfVolume(model, ws, mid) > top_pa ? hi : lo) = mid;
  }
  return lo;
}

std::string volumeNotFollowedMessage(double supplied_volume_m3, bool solver_failure, double volume_limit_m3) {
  return "supplied volume " + formatMessage(supplied_volume_m3) + " m^3 is " +
         (solver_failure ? std::string("one the solver found no finite answer for")
                         : "at or beyond the most the model follows, " + formatMessage(volume_limit_m3) +
                               " m^3 (the gas in the drive snaps the finger there, or the wall locks)");
}

VolumeCheck checkVolumeRange(double supplied_volume_m3, double max_supplied_volume_m3) {
  VolumeCheck c;
  c.volume_m3 = supplied_volume_m3;
  if (supplied_volume_m3 > max_supplied_volume_m3 && std::isfinite(supplied_volume_m3)) {
    c.clamped = true;
    c.volume_m3 = max_supplied_volume_m3;
  }
  return c;
}

std::string volumeClampedMessage(double supplied_volume_m3, double max_supplied_volume_m3, const PressureRange& range) {
  return "supplied volume " + formatMessage(supplied_volume_m3) + " m^3 is above " +
         formatMessage(max_supplied_volume_m3) + " m^3, the volume that makes max_gauge_pa " +
         formatMessage(range.max_gauge_pa) + " Pa (the top of the model's range): clamped to it";
}

std::size_t clampVolumesToRange(const double* in, double* out, std::size_t count, double max_supplied_volume_m3) {
  std::size_t clamped = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const VolumeCheck c = checkVolumeRange(in[i], max_supplied_volume_m3);
    out[i] = c.volume_m3;
    clamped += c.clamped ? 1 : 0;
  }
  return clamped;
}

}  // namespace pneumatic_finger
