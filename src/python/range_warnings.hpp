// The range rule's words as Python's RuntimeWarnings: the same words finger_model prints on stderr and finger_node
// gives in its diagnostics (pressure_range.hpp). Internal header of the Python module (src/python).
#pragma once

#include <pybind11/pybind11.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "pneumatic_finger/core/pressure_range.hpp"

namespace pneumatic_finger_python {

namespace py = pybind11;
namespace pf = pneumatic_finger;

inline void warnRuntime(const std::string& what) {
  if (PyErr_WarnEx(PyExc_RuntimeWarning, what.c_str(), 1) != 0) throw py::error_already_set();
}

/// A clamp, once per call, for the first pressure above the range (and how many more).
inline void warnClamped(const double* p, std::size_t count, std::size_t clamped, const pf::PressureRange& range) {
  const double* first = std::find_if(p, p + count, [&range](double x) { return pf::checkGaugeRange(x, range).clamped; });
  warnRuntime(pf::clampedMessage(*first, range) +
              (clamped > 1 ? " (and " + std::to_string(clamped - 1) + " more)" : std::string()));
}

/// The rule's other words, once per call each, for the first such pressure: a vacuum, and a pressure above the
/// validated range that was not clamped (in a file no actuator validates: every pressure above 0).
inline void warnOutsideValidated(const double* p, std::size_t count, const pf::PressureRange& range) {
  const double* not_finite = std::find_if(p, p + count, [](double x) { return !std::isfinite(x); });
  if (not_finite != p + count) warnRuntime(pf::notFinitePressureMessage(*not_finite) + ": its row is nan");
  const double* vacuum = std::find_if(p, p + count, [](double x) { return x < 0; });
  if (vacuum != p + count) warnRuntime(pf::vacuumMessage(*vacuum));
  const double* above = std::find_if(p, p + count, [&range](double x) {
    const pf::RangeCheck c = pf::checkGaugeRange(x, range);
    return c.above_validated && !c.clamped;
  });
  if (above != p + count) warnRuntime(pf::aboveValidatedMessage(*above, range));
}

/// A volume the model does not follow (its row NaN), once per call, in finger_model's and the node's words: one that
/// is not finite, or (from the rows' statuses, when asked for) one past the most the model follows.
inline void warnVolumeNotFollowed(const double* v, const std::uint8_t* status, std::size_t count,
                                  double volume_limit_m3) {
  const double* not_finite = std::find_if(v, v + count, [](double x) { return !std::isfinite(x); });
  if (not_finite != v + count) warnRuntime(pf::notFiniteVolumeMessage(*not_finite) + ": its row is nan");
  for (std::size_t i = 0; status && i < count; ++i) {
    const auto s = static_cast<pf::EvaluationStatus>(status[i]);
    if (s != pf::EvaluationStatus::kBeyondLimitPoint && s != pf::EvaluationStatus::kSolverFailure) continue;
    if (!std::isfinite(v[i])) continue;  // said above
    warnRuntime(pf::volumeNotFollowedMessage(v[i], s == pf::EvaluationStatus::kSolverFailure, volume_limit_m3) +
                "; its row is nan");
    return;
  }
}

/// A gauge pressure below the vacuum's floor (a negative absolute pressure), refused as every interface refuses it:
/// ValueError naming its index (none for a scalar).
inline void refuseNegativeAbsolute(const double* p, std::size_t count, bool scalar, double atmospheric_pa) {
  for (std::size_t i = 0; i < count; ++i) {
    if (!(p[i] + atmospheric_pa < 0.0)) continue;
    throw py::value_error("gauge_pa" + (scalar ? std::string() : "[" + std::to_string(i) + "]") + ": " +
                          pf::negativeAbsoluteMessage(p[i] + atmospheric_pa));
  }
}

}  // namespace pneumatic_finger_python
