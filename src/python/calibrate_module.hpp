// pf.calibrate: the calibration finger_calibrate runs (calibration/calibration_run.hpp), on a CSV path or on columns of
// numbers. Internal header of the Python module (src/python).
#pragma once

#include <pybind11/pybind11.h>

namespace pneumatic_finger_python {

/// Defines _core.calibrate (and design_to_target, defineDesign) in @p m.
void defineCalibrate(pybind11::module_& m);

/// Defines _core.design_to_target in @p m (design_module.cpp).
void defineDesign(pybind11::module_& m);

}  // namespace pneumatic_finger_python
