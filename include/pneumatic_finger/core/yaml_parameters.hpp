// Loading and writing the actuator's parameter file (config/finger.yaml): the same file finger_model,
// finger_calibrate and the node read. Validation is FingerParameters::fromRaw's, so every reader refuses the
// same things with the same message.
#pragma once

#include <string>

#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/tip_uncertainty.hpp"

namespace pneumatic_finger {

/// Reads a YAML mapping of keys (parameterSpecs()) to numbers or lists of numbers.
/// @param[in] path file to read
/// @param[in,out] raw values are added to (and override) what @p raw holds
/// @param[out] tip_uncertainty when given, the file's error bar (tip_uncertainty), read from the same parse
/// @throws ParameterError naming the file and the key for an unreadable file, malformed YAML, a key whose value
///         is not a number or a list of numbers, or an unknown key
void loadRawParametersFromYamlFile(const std::string& path, RawParameterMap& raw,
                                   TipUncertainty* tip_uncertainty = nullptr);

/// Same as loadRawParametersFromYamlFile for YAML text; @p origin names it in messages.
void loadRawParametersFromYamlText(const std::string& text, const std::string& origin, RawParameterMap& raw,
                                   TipUncertainty* tip_uncertainty = nullptr);

/// The parameter file text for @p parameters: every key, with its unit and meaning as a comment.
std::string parametersToYaml(const FingerParameters& parameters);

}  // namespace pneumatic_finger
