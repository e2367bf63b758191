#include "pneumatic_finger/core/yaml_parameters.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "pneumatic_finger/core/drawing.hpp"
#include "yaml_node.hpp"

namespace pneumatic_finger {

namespace {

double toNumber(const YAML::Node& node, const std::string& key, const std::string& origin) {
  const ParameterSpec* spec = findParameterSpec(key);
  if (spec != nullptr && spec->shape == ParameterShape::kChoice) {
    if (!node.IsScalar()) throw ParameterError(origin + ": parameter '" + key + "' must be " + describeRange(*spec));
    try {
      return parseParameterText(*spec, node.Scalar());
    } catch (const ParameterError& e) {
      throw ParameterError(origin + ": " + e.what());
    }
  }
  if (!node.IsScalar()) throw ParameterError(origin + ": parameter '" + key + "' must be a number");
  try {
    return node.as<double>();
  } catch (const YAML::Exception&) {
    throw ParameterError(origin + ": parameter '" + key + "' = '" + node.Scalar() + "' is not a number");
  }
}

const ParameterSpec* findRangeSpec(const std::string& key) {
  for (const ParameterSpec& spec : rangeParameterSpecs()) {
    if (key == spec.key) return &spec;
  }
  return nullptr;
}

bool isNodeInterfaceKey(const std::string& key) {
  const std::vector<std::string>& keys = nodeInterfaceKeys();
  return std::find(keys.begin(), keys.end(), key) != keys.end();
}

// The file's range keys onto @p range, each checked by the one rule, and the validated range within the model's.
void rangeFromNode(const YAML::Node& root, const std::string& origin, PressureRange& range) {
  if (!root.IsMap()) return;
  for (const ParameterSpec& spec : rangeParameterSpecs()) {
    const YAML::Node node = root[spec.key];
    if (!node) continue;
    if (!node.IsScalar()) throw ParameterError(origin + ": parameter '" + spec.key + "' must be a number");
    const double value = toNumber(node, spec.key, origin);
    try {
      checkParameterValue(spec, value);
    } catch (const ParameterError& e) {
      throw ParameterError(origin + ": " + e.what());
    }
    (std::string(spec.key) == "max_gauge_pa" ? range.max_gauge_pa : range.validated_max_gauge_pa) = value;
  }
  if (!root["validated_max_gauge_pa"]) range.validated_max_gauge_pa = std::min(range.validated_max_gauge_pa, range.max_gauge_pa);
  if (range.validated_max_gauge_pa > range.max_gauge_pa) {
    throw ParameterError(origin + ": validated_max_gauge_pa = " + formatMessage(range.validated_max_gauge_pa) +
                         " Pa is above max_gauge_pa = " + formatMessage(range.max_gauge_pa) +
                         " Pa: the validated range lies within the model's");
  }
}

// The drawing's mapping (docs/DRAWING.md), each key with its meaning; empty without a drawing.
std::string drawingToYaml(const RawParameterMap& drawing) {
  if (drawing.empty()) return "";
  std::ostringstream out;
  out << "# the actuator as drawn (docs/DRAWING.md): the model keys above marked (from the drawing) follow from it\n"
      << "drawing:\n";
  for (const ParameterSpec& spec : drawingParameterSpecs()) {
    const auto it = drawing.find(kDrawingPrefix + std::string(spec.key));
    if (it == drawing.end()) continue;
    out << "  # " << spec.description << " (" << spec.unit << ")\n"
        << "  " << spec.key << ": " << formatYamlNumber(it->second.values[0]) << "\n";
  }
  return out.str();
}

// The file's drawing mapping into @p raw as "drawing/KEY" entries.
void drawingFromNode(const YAML::Node& node, const std::string& origin, RawParameterMap& raw) {
  if (!node.IsMap()) throw ParameterError(origin + ": 'drawing' must be a mapping of the drawing's keys to numbers");
  for (const auto& item : node) {
    const std::string key = kDrawingPrefix + item.first.as<std::string>();
    if (!isDrawingKey(key)) throw unknownParameterError(key, origin);  // named with its file, as a top-level key is
    if (!item.second.IsScalar()) throw ParameterError(origin + ": parameter '" + key + "' must be a number");
    try {
      raw[key] = {{item.second.as<double>()}, false};
    } catch (const YAML::Exception&) {
      throw ParameterError(origin + ": parameter '" + key + "' = '" + item.second.Scalar() + "' is not a number");
    }
  }
}

// The tree's actuator keys into @p raw; finger_node's own keys into @p node_keys (the node reads them, every other
// interface ignores them); any other key is refused, in unknownParameterError's words.
void fromNode(const YAML::Node& root, const std::string& origin, RawParameterMap& raw,
              std::vector<std::string>& node_keys) {
  if (root.IsNull()) return;  // an empty file: all defaults
  if (!root.IsMap()) throw ParameterError(origin + ": expected a mapping of parameter keys to values");
  for (const auto& item : root) {
    const std::string key = item.first.as<std::string>();
    if (key == kTipUncertaintyKey) continue;  // not the actuator: the calibration's error bar (tip_uncertainty.hpp)
    if (key == kCalibrationErrorKey) continue;  // nor how well it followed its data (calibration_error.hpp)
    if (key == "drawing") {
      drawingFromNode(item.second, origin, raw);
      continue;
    }
    if (findRangeSpec(key) != nullptr) continue;  // the range's: rangeFromNode
    if (isNodeInterfaceKey(key)) {
      node_keys.push_back(key);
      continue;
    }
    if (findParameterSpec(key) == nullptr) throw unknownParameterError(key, origin);
    RawParameterValue value;
    if (item.second.IsSequence()) {
      value.is_list = true;
      for (const auto& element : item.second) value.values.push_back(toNumber(element, key, origin));
      if (value.values.empty()) throw ParameterError(origin + ": parameter '" + key + "' is an empty list");
    } else {
      value.values.push_back(toNumber(item.second, key, origin));
    }
    raw[key] = value;
  }
}

}  // namespace

const std::vector<ParameterSpec>& rangeParameterSpecs() {
  static const std::vector<ParameterSpec> specs = {
      {"max_gauge_pa", "P_max", "Pa", kModelMaxGaugePa, 0.0, false, 1e7, ParameterShape::kScalar,
       "top of the model's range: a higher pressure (or the volume that makes it) is clamped to it"},
      {"validated_max_gauge_pa", "P_val", "Pa", kValidatedMaxGaugePa, 0.0, true, 1e7, ParameterShape::kScalar,
       "top of the validated range (written by finger_calibrate: the highest pressure it calibrated on); above it "
       "the twin extrapolates and says so; 0: no actuator's data validate the file (a drawing, a coupon), and every "
       "answer above 0 Pa is a zero-shot prediction"}};
  return specs;
}

const ParameterSpec& rangeParameterSpec(const std::string& key) {
  for (const ParameterSpec& spec : rangeParameterSpecs()) {
    if (key == spec.key) return spec;
  }
  throw std::out_of_range("'" + key + "' is not a range key");
}

const std::vector<std::string>& nodeInterfaceKeys() {
  static const std::vector<std::string> keys = {
      "frame_prefix",       "parent_frame",      "mount_xyz_m",          "mount_rpy_rad",      "gripper_file",
      "solver",             "publish_tf",        "max_rate_hz",          "stale_timeout_s",    "stamp_tolerance_s",
      "time_jump_s",        "description_param", "pressure_topic",       "volume_topic",       "joint_states_topic",
      "finger_state_topic", "grasp_object_topic", "object_rate_hz",      "transform_timeout_s", "force_arrow_m_per_n"};
  return keys;
}

std::string rangeToYaml(const PressureRange& range) {
  std::ostringstream out;
  for (const ParameterSpec& spec : rangeParameterSpecs()) {
    const double value = std::string(spec.key) == "max_gauge_pa" ? range.max_gauge_pa : range.validated_max_gauge_pa;
    out << "# " << spec.description << " (" << spec.unit << ", allowed " << describeRange(spec) << ")\n"
        << spec.key << ": " << formatYamlNumber(value) << "\n";
  }
  return out.str();
}

ParameterTree readParameterTree(const YAML::Node& root, const std::string& origin) {
  ParameterTree tree;
  fromNode(root, origin, tree.raw, tree.node_keys);
  rangeFromNode(root, origin, tree.range);  // checked for every reader, as the error bar is
  tree.tip_uncertainty = tipUncertaintyFromYamlNode(root, origin);
  tree.calibration_error = calibrationErrorFromYamlNode(root, origin);
  return tree;
}

void loadRawParametersFromYamlText(const std::string& text, const std::string& origin, RawParameterMap& raw,
                                   TipUncertainty* tip_uncertainty, PressureRange* range,
                                   CalibrationError* calibration_error) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ParameterError(origin + ": not valid YAML: " + e.what());
  }
  ParameterTree tree = readParameterTree(root, origin);
  for (auto& [key, value] : tree.raw) raw[key] = std::move(value);
  // A malformed range or error bar is refused by every reader of the file, whether it asked for it or not.
  if (range != nullptr) *range = tree.range;
  if (tip_uncertainty != nullptr) *tip_uncertainty = tree.tip_uncertainty;
  if (calibration_error != nullptr) *calibration_error = tree.calibration_error;
}

void loadRawParametersFromYamlFile(const std::string& path, RawParameterMap& raw, TipUncertainty* tip_uncertainty,
                                   PressureRange* range, CalibrationError* calibration_error) {
  std::ifstream in(path);
  if (!in) throw ParameterError("cannot read parameter file '" + path + "'");
  std::stringstream text;
  text << in.rdbuf();
  loadRawParametersFromYamlText(text.str(), path, raw, tip_uncertainty, range, calibration_error);
}

std::string parametersToYaml(const FingerParameters& parameters) {
  std::ostringstream out;
  const RawParameterMap raw = resolveDrawing(parameters.toRaw());
  const std::vector<std::string>& drawn = drawnModelKeys();
  for (const ParameterSpec& spec : parameterSpecs()) {
    const RawParameterValue& v = raw.at(spec.key);
    out << "# " << spec.description << " (" << spec.symbol << ", " << spec.unit << ", allowed "
        << describeRange(spec) << ")\n";
    // A drawn key is the drawing's: written as a comment, so that the file keeps one definition of it.
    const bool from_drawing = !parameters.drawing.empty() && std::find(drawn.begin(), drawn.end(), spec.key) != drawn.end();
    out << (from_drawing ? "# (from the drawing) " : "") << spec.key << ": ";
    if (v.is_list) {
      out << "[";
      for (std::size_t i = 0; i < v.values.size(); ++i) out << (i ? ", " : "") << formatYamlNumber(v.values[i]);
      out << "]";
    } else {
      out << formatParameterValue(spec, v.values[0]);
    }
    out << "\n";
  }
  return out.str() + drawingToYaml(parameters.drawing);
}

}  // namespace pneumatic_finger
