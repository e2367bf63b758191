// The parameter file's error bar from an already parsed document: the file is parsed once, and its keys
// (yaml_parameters.cpp) and its tip_uncertainty mapping (tip_uncertainty.cpp) are read from the same tree. Internal
// header of src/core.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

#include "pneumatic_finger/core/calibration_error.hpp"
#include "pneumatic_finger/core/tip_uncertainty.hpp"

namespace pneumatic_finger {

/// The tip_uncertainty mapping of the document @p root (empty when it has none). @throws ParameterError naming
/// @p origin for a malformed entry
TipUncertainty tipUncertaintyFromYamlNode(const YAML::Node& root, const std::string& origin);

/// The calibration_error mapping of the document @p root (empty when it has none). @throws ParameterError naming
/// @p origin for a malformed entry
CalibrationError calibrationErrorFromYamlNode(const YAML::Node& root, const std::string& origin);

}  // namespace pneumatic_finger
