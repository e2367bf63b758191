// pf.range_check: the model's range rule, as every interface applies it (core/pressure_range.hpp). Internal header
// of the Python module (src/python).
#pragma once

#include <pybind11/pybind11.h>

namespace pneumatic_finger_python {

/// Defines _core.range_check in @p m.
void defineRangeCheck(pybind11::module_& m);

}  // namespace pneumatic_finger_python
