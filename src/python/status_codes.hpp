// The status codes Python sees: pf.STATUS and pf.CONTACT_STATUS name them, and the arrays carry them as uint8.
// Internal header of the Python module (src/python).
#pragma once

#include <cstdint>
#include <vector>

#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/evaluation.hpp"

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

}  // namespace pneumatic_finger_python
