// The model's pressure range (pressure_range.hpp).
#include "pneumatic_finger/core/pressure_range.hpp"

#include <algorithm>
#include <cmath>

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

RangeCheck checkGaugeRange(double gauge_pa, const PressureRange& range) {
  RangeCheck c;
  c.gauge_pa = gauge_pa;
  c.above_validated = gauge_pa > range.validated_max_gauge_pa;
  if (gauge_pa > range.max_gauge_pa && std::isfinite(gauge_pa)) {  // +inf is not a pressure: the model refuses it
    c.clamped = true;
    c.gauge_pa = range.max_gauge_pa;
  }
  return c;
}

std::string clampedMessage(double gauge_pa, const PressureRange& range) {
  return "gauge pressure " + formatMessage(gauge_pa) + " Pa is above max_gauge_pa " +
         formatMessage(range.max_gauge_pa) + " Pa, the top of the model's range: clamped to it";
}

std::string vacuumMessage(double gauge_pa) {
  return "gauge pressure " + formatMessage(gauge_pa) + " Pa is a vacuum, outside the model: the straight finger";
}

std::string aboveValidatedMessage(double gauge_pa, const PressureRange& range) {
  return "gauge pressure " + formatMessage(gauge_pa) + " Pa is above the validated range (0 to " +
         formatMessage(range.validated_max_gauge_pa) + " Pa): the twin extrapolates";
}

std::size_t clampToRange(const double* in, double* out, std::size_t count, const PressureRange& range) {
  std::size_t clamped = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const RangeCheck c = checkGaugeRange(in[i], range);
    out[i] = c.gauge_pa;
    clamped += c.clamped ? 1 : 0;
  }
  return clamped;
}

void markClamped(const double* in, std::uint8_t* status, std::size_t count, const PressureRange& range) {
  const auto ok = static_cast<std::uint8_t>(EvaluationStatus::kOk);
  for (std::size_t i = 0; i < count; ++i) {
    if (checkGaugeRange(in[i], range).clamped && status[i] == ok) {
      status[i] = static_cast<std::uint8_t>(EvaluationStatus::kClamped);
    }
  }
}

}  // namespace pneumatic_finger
