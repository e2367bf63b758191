// A parameter file with Python's overrides on top, as a raw map that every reader validates the same way. Internal
// header of the Python module (src/python).
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "pneumatic_finger/core/drawing.hpp"
#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pneumatic_finger_python {

namespace py = pybind11;
namespace pf = pneumatic_finger;

// Python's value of an override: a number, or a list of numbers (one per chamber).
inline pf::RawParameterValue rawValue(const std::string& key, const py::handle& value) {
  pf::RawParameterValue raw;
  try {
    const pf::ParameterSpec* spec = pf::findParameterSpec(key);
    if (spec != nullptr && spec->shape == pf::ParameterShape::kChoice && py::isinstance<py::str>(value)) {
      raw.values.push_back(pf::parseParameterText(*spec, value.cast<std::string>()));
    } else if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
      raw.values.push_back(value.cast<double>());
    } else {
      raw.is_list = true;
      for (const py::handle& v : value) raw.values.push_back(v.cast<double>());
    }
  } catch (const py::cast_error&) {
    throw pf::ParameterError("parameter '" + key + "' must be a number or a list of numbers");
  } catch (const py::type_error&) {
    throw pf::ParameterError("parameter '" + key + "' must be a number or a list of numbers");
  }
  return raw;
}

// A parameter file with Python overrides on top: the raw map every reader validates the same way.
inline pf::RawParameterMap loadRaw(const std::string& config, const py::dict& overrides,
                                   pf::PressureRange* range = nullptr) {
  pf::RawParameterMap raw;
  if (!config.empty()) pf::loadRawParametersFromYamlFile(config, raw, nullptr, range);
  for (const auto& item : overrides) {
    const std::string key = py::str(item.first);
    raw[key] = rawValue(key, item.second);
  }
  return raw;
}

/// The actuator's keys as Python values: numbers, lists per chamber, choices by name; a drawn actuator's drawing as a
/// dict under "drawing" (docs/DRAWING.md).
inline py::dict parametersDict(const pf::FingerParameters& parameters) {
  py::dict d;
  py::dict drawing;
  for (const auto& kv : pf::resolveDrawing(parameters.toRaw())) {
    if (kv.first.rfind(pf::kDrawingPrefix, 0) == 0) {  // the drawing's sizes, under "drawing"
      drawing[py::str(kv.first.substr(std::string(pf::kDrawingPrefix).size()))] = py::float_(kv.second.values[0]);
      continue;
    }
    const pf::ParameterSpec& spec = *pf::findParameterSpec(kv.first);
    if (kv.second.is_list) {
      d[py::str(kv.first)] = py::cast(kv.second.values);
    } else if (spec.shape == pf::ParameterShape::kChoice) {
      d[py::str(kv.first)] = py::str(pf::formatParameterValue(spec, kv.second.values[0]));
    } else {
      d[py::str(kv.first)] = py::float_(kv.second.values[0]);
    }
  }
  if (!drawing.empty()) d["drawing"] = drawing;
  return d;
}

}  // namespace pneumatic_finger_python
