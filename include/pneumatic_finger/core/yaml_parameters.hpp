// Loading and writing the actuator's parameter file (config/finger.yaml): the same file finger_model,
// finger_calibrate and the node read. Validation is FingerParameters::fromRaw's, so every reader refuses the
// same things with the same message.
#pragma once

#include <string>
#include <vector>

#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/pressure_range.hpp"
#include "pneumatic_finger/core/calibration_error.hpp"
#include "pneumatic_finger/core/tip_uncertainty.hpp"

namespace YAML {
class Node;
}

namespace pneumatic_finger {

/// What a parameter tree says: the one reading of a parameter file that every interface calls, whether the tree came
/// from a file (finger_model, the tools, Python, a gripper file's finger) or is finger_node's private namespace, which
/// rosparam loaded from the same file (the node hands it over whole, as robot_state_publisher reads its description).
struct ParameterTree {
  RawParameterMap raw;              ///< the actuator's keys as given (model keys; the drawing's as drawing/KEY)
  PressureRange range;              ///< max_gauge_pa and validated_max_gauge_pa, by the one rule (rangeParameterSpecs)
  TipUncertainty tip_uncertainty;   ///< the calibration's error bar (empty without one)
  CalibrationError calibration_error;  ///< how well the calibration followed its data (empty without one)
  std::vector<std::string> node_keys;  ///< the keys left unclaimed: finger_node's own (nodeInterfaceKeys), for it
};

/// Reads @p root, a mapping of parameter keys. Any key that is not the actuator's, the range's, the error bar's or
/// the node's is refused (unknownParameterError); values are checked as the file's (FingerParameters::fromRaw checks
/// the actuator's as a whole). The validated range, when the tree gives only max_gauge_pa, is no higher than it.
/// @throws ParameterError naming @p origin and the key
ParameterTree readParameterTree(const YAML::Node& root, const std::string& origin);

/// Reads a YAML mapping of keys (parameterSpecs()) to numbers or lists of numbers.
/// @param[in] path file to read
/// @param[in,out] raw values are added to (and override) what @p raw holds
/// @param[out] tip_uncertainty when given, the file's error bar (tip_uncertainty), read from the same parse
/// @throws ParameterError naming the file and the key for an unreadable file, malformed YAML, a key whose value
///         is not a number or a list of numbers, or an unknown key
/// @param[in,out] range when given, the file's max_gauge_pa and validated_max_gauge_pa (rangeParameterSpecs) replace
///        its fields; the keys are checked whether it is given or not
/// One file serves every interface: the range keys are read by each (finger_node, finger_model, Python),
/// and finger_node's own keys (nodeInterfaceKeys: topics, rates, frames) are left to the node by the others.
/// @param[out] calibration_error when given, the file's calibration_error (how well its calibration followed its data)
void loadRawParametersFromYamlFile(const std::string& path, RawParameterMap& raw,
                                   TipUncertainty* tip_uncertainty = nullptr, PressureRange* range = nullptr,
                                   CalibrationError* calibration_error = nullptr);

/// Same as loadRawParametersFromYamlFile for YAML text; @p origin names it in messages.
void loadRawParametersFromYamlText(const std::string& text, const std::string& origin, RawParameterMap& raw,
                                   TipUncertainty* tip_uncertainty = nullptr, PressureRange* range = nullptr,
                                   CalibrationError* calibration_error = nullptr);

/// The parameter file's range keys: max_gauge_pa (the top of the model's range) and validated_max_gauge_pa (the top
/// of the pressures its calibration saw: finger_calibrate writes it). Every interface reads them from the file.
const std::vector<ParameterSpec>& rangeParameterSpecs();
/// One of rangeParameterSpecs by its key. @throws std::out_of_range for another key.
const ParameterSpec& rangeParameterSpec(const std::string& key);

/// finger_node's keys that a parameter file may carry (volume_topic, frame_prefix, ...): the other interfaces accept
/// and ignore them. test_finger_node holds this list to the node's own parameter table.
const std::vector<std::string>& nodeInterfaceKeys();

/// The range keys' text for a parameter file, commented, in formatYamlNumber's numbers.
std::string rangeToYaml(const PressureRange& range);

/// The parameter file text for @p parameters: every key, with its unit and meaning as a comment.
std::string parametersToYaml(const FingerParameters& parameters);

}  // namespace pneumatic_finger
