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
#include "pneumatic_finger/core/evaluation_report.hpp"
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

// pf.STATUS (by code), pf.STATUS_FLAGS (by bit: status_flags' bit b is STATUS_FLAGS[b]) and pf.CONTACT_STATUS.
inline void defineStatusNames(pybind11::module_& m) {
  namespace py = pybind11;
  m.attr("STATUS") = py::tuple(py::cast(evaluationStatusNames()));
  std::vector<std::string> flag_names;
  for (int bit = 0; bit < pf::kStatusFlagCount; ++bit) flag_names.emplace_back(pf::statusFlagName(bit));
  m.attr("STATUS_FLAGS") = py::tuple(py::cast(flag_names));
  m.attr("CONTACT_STATUS") = py::tuple(py::cast(std::vector<std::string>(kContactStatus.begin(), kContactStatus.end())));
}

inline std::uint8_t contactStatusCode(pf::ContactState::Status status) {
  using S = pf::ContactState::Status;
  return status == S::kFree             ? 0
         : status == S::kInContact      ? 1
         : status == S::kOverlapsAtRest ? 2
         : status == S::kSolverFailure  ? 3
                                        : 4;
}

// The flags need the model's status: a scratch it is written into where the caller asked for flags and not for the
// status (rows.status points into the returned vector, whose buffer a move keeps), else empty.
inline std::vector<std::uint8_t> statusForFlags(pf::BatchOutputs& rows, const std::uint8_t* flags, std::size_t count) {
  std::vector<std::uint8_t> storage;
  if (!flags || rows.status) return storage;
  storage.resize(count);
  rows.status = storage.data();
  return storage;
}

// Each row reported by the core's one rule (evaluation_report.hpp), as finger_node reports its finger_state:
// @p rows.status (the model's, when given) becomes the interfaces' status and @p flags (when given) its flags;
// @p range_of(i) is row i's range check. @p rows.joint_angle_rad must be written (count x N). Returns the first
// self-crossing row's tip angle (NaN: none), for the warning.
template <class RangeOf>
double reportRows(const pf::FingerParameters& parameters, const pf::BatchOutputs& rows, std::uint8_t* flags,
                  std::size_t count, RangeOf range_of) {
  const auto n = static_cast<std::size_t>(parameters.chamber_count);
  double first = NAN;
  for (std::size_t i = 0; i < count; ++i) {
    const double* q = rows.joint_angle_rad + i * n;
    const bool meets = pf::jointsMeetThemselves(parameters, q);  // NaN rows never do
    if (meets && std::isnan(first)) first = std::accumulate(q, q + n, 0.0);
    if (!rows.status) continue;
    const pf::EvaluationReport report =
        pf::reportEvaluation(static_cast<pf::EvaluationStatus>(rows.status[i]), range_of(i), meets);
    rows.status[i] = static_cast<std::uint8_t>(report.status);
    if (flags) flags[i] = report.flags;
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
