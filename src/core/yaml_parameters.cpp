#include "pneumatic_finger/core/yaml_parameters.hpp"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <sstream>

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

void fromNode(const YAML::Node& root, const std::string& origin, RawParameterMap& raw) {
  if (root.IsNull()) return;  // an empty file: all defaults
  if (!root.IsMap()) throw ParameterError(origin + ": expected a mapping of parameter keys to values");
  for (const auto& item : root) {
    const std::string key = item.first.as<std::string>();
    if (key == kTipUncertaintyKey) continue;  // not the actuator: the calibration's error bar (tip_uncertainty.hpp)
    if (findParameterSpec(key) == nullptr) throw ParameterError(origin + ": unknown parameter '" + key + "'");
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

void loadRawParametersFromYamlText(const std::string& text, const std::string& origin, RawParameterMap& raw,
                                   TipUncertainty* tip_uncertainty) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ParameterError(origin + ": not valid YAML: " + e.what());
  }
  fromNode(root, origin, raw);
  // A malformed error bar is refused by every reader of the file, whether it asked for it or not.
  const TipUncertainty read = tipUncertaintyFromYamlNode(root, origin);
  if (tip_uncertainty != nullptr) *tip_uncertainty = read;
}

void loadRawParametersFromYamlFile(const std::string& path, RawParameterMap& raw, TipUncertainty* tip_uncertainty) {
  std::ifstream in(path);
  if (!in) throw ParameterError("cannot read parameter file '" + path + "'");
  std::stringstream text;
  text << in.rdbuf();
  loadRawParametersFromYamlText(text.str(), path, raw, tip_uncertainty);
}

std::string parametersToYaml(const FingerParameters& parameters) {
  std::ostringstream out;
  const RawParameterMap raw = parameters.toRaw();
  for (const ParameterSpec& spec : parameterSpecs()) {
    const RawParameterValue& v = raw.at(spec.key);
    out << "# " << spec.description << " (" << spec.symbol << ", " << spec.unit << ", allowed "
        << describeRange(spec) << ")\n"
        << spec.key << ": ";
    if (v.is_list) {
      out << "[";
      for (std::size_t i = 0; i < v.values.size(); ++i) out << (i ? ", " : "") << formatShortest(v.values[i]);
      out << "]";
    } else {
      out << formatParameterValue(spec, v.values[0]);
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace pneumatic_finger
