// The status codes Python sees: pf.STATUS and pf.CONTACT_STATUS name them, the arrays carry them as uint8, and the
// interfaces' own statuses (meets itself) are marked here. Internal header of the Python module (src/python).
#pragma once

#include <pybind11/pybind11.h>

#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/evaluation.hpp"
#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/self_contact.hpp"

namespace pneumatic_finger_python {

namespace pf = pneumatic_finger;

// The status codes' names, indexed by code: pf.STATUS and pf.CONTACT_STATUS in Python.
inline std::vector<const char*> evaluationStatusNames() {
  std::vector<const char*> names;
  for (std::uint8_t code = 0; code < pf::kEvaluationStatusCount; ++code) {
    names.push_back(pf::evaluationStatusName(static_cast<pf::EvaluationStatus>(code)));
  }
  return names;
}
inline const std::vector<const char*> kContactStatus = {"free", "in contact", "overlaps at rest", "solver failure",
                                                        "beyond limit point"};

inline std::uint8_t contactStatusCode(pf::ContactState::Status status) {
  using S = pf::ContactState::Status;
  return status == S::kFree             ? 0
         : status == S::kInContact      ? 1
         : status == S::kOverlapsAtRest ? 2
         : status == S::kSolverFailure  ? 3
                                        : 4;
}

// Rows whose backbone crosses itself (self_contact.hpp) get status 'meets itself', as finger_node's; returns the
// first one's tip angle (NaN: none). @p rows.joint_angle_rad must be written (count x N).
inline double markSelfContact(const pf::FingerParameters& parameters, const pf::BatchOutputs& rows, std::size_t count) {
  const auto n = static_cast<std::size_t>(parameters.chamber_count);
  double first = NAN;
  for (std::size_t i = 0; i < count; ++i) {
    const double* q = rows.joint_angle_rad + i * n;
    if (!pf::jointsMeetThemselves(parameters, q)) continue;  // NaN rows never do
    if (std::isnan(first)) first = std::accumulate(q, q + n, 0.0);
    if (rows.status && rows.status[i] != static_cast<std::uint8_t>(pf::EvaluationStatus::kVacuum)) {
      rows.status[i] = static_cast<std::uint8_t>(pf::EvaluationStatus::kMeetsItself);
    }
  }
  return first;
}

// The words every interface says for it, once per call, as a RuntimeWarning (nothing for NaN: no row met itself).
inline void warnSelfContact(double tip_angle_rad) {
  if (std::isnan(tip_angle_rad)) return;
  const std::string what = pf::selfContactMessage(tip_angle_rad);
  if (PyErr_WarnEx(PyExc_RuntimeWarning, what.c_str(), 1) != 0) throw pybind11::error_already_set();
}

}  // namespace pneumatic_finger_python
