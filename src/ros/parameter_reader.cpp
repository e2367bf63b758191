// The one reader of a node's private handle. Numbers go through the core's checkParameterValue, so a node's
// parameter and an actuator key in a YAML file are refused by the same rule, in the same words.
#include "pneumatic_finger/ros/parameter_reader.hpp"

#include <ros/names.h>

#include <cctype>
#include <cstdlib>
#include <iostream>
#include <sstream>

namespace pneumatic_finger {

namespace {

// The core's spec of a node number (its strings outlive the call), so that the core's checker judges it.
ParameterSpec asCoreSpec(const NodeParameterSpec& sp, double max_value) {
  const ParameterShape shape = sp.type == "int" ? ParameterShape::kScalarInteger : ParameterShape::kScalar;
  return {sp.key.c_str(), "", sp.unit.c_str(), sp.default_value, sp.min_value, !sp.min_open,
          max_value,      shape, sp.description.c_str()};
}

}  // namespace

namespace {

// YAML 1.1 (rosparam) reads "1e-05" as a string where yaml-cpp, finger_model and Python read a number: the node takes
// a string that is one whole number, so that a hand-written file loads the same everywhere ("fast" is still refused).
bool parseNumberText(const std::string& text, double& out) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return false;
  const std::optional<double> value = readNumber(text);
  if (!value) return false;
  out = *value;
  return true;
}

}  // namespace

bool asParameterNumber(const XmlRpc::XmlRpcValue& v, double& out) {
  auto& x = const_cast<XmlRpc::XmlRpcValue&>(v);
  if (x.getType() == XmlRpc::XmlRpcValue::TypeDouble) out = static_cast<double>(x);
  else if (x.getType() == XmlRpc::XmlRpcValue::TypeInt) out = static_cast<int>(x);
  else if (x.getType() == XmlRpc::XmlRpcValue::TypeString) return parseNumberText(static_cast<std::string>(x), out);
  else return false;
  return true;
}

namespace {

std::string rangeText(double lo, bool lo_open, double hi, bool integer) {
  const ParameterSpec range{"", "", "", 0, lo, !lo_open, hi,
                            integer ? ParameterShape::kScalarInteger : ParameterShape::kScalar, ""};
  return describeRange(range);
}

}  // namespace

NodeParameterSpec numberParameter(const char* key, double def, double lo, bool lo_open, double hi, const char* unit,
                                  const char* description, const char* allowed) {
  return {key, "double", formatShortest(def), def, lo, lo_open, hi, unit,
          allowed ? allowed : rangeText(lo, lo_open, hi, false), description};
}

NodeParameterSpec coreNumberParameter(const ParameterSpec& core, const char* node_use, const char* allowed) {
  const std::string description = std::string(core.description) + "; " + node_use;
  NodeParameterSpec spec = numberParameter(core.key, core.default_value, core.min_value, !core.min_inclusive,
                                           core.max_value, core.unit, "", allowed);
  spec.description = description;
  return spec;
}

NodeParameterSpec integerParameter(const char* key, int def, int lo, int hi, const char* description) {
  return {key, "int", std::to_string(def), double(def), double(lo), false, double(hi), "-", rangeText(lo, false, hi, true),
          description};
}

NodeParameterSpec textParameter(const char* key, const std::string& def, const char* allowed, const char* description) {
  return {key, "string", def, 0, 0, false, 0, "-", allowed, description};
}

NodeParameterSpec flagParameter(const char* key, bool def, const char* description) {
  return {key, "bool", def ? "true" : "false", def ? 1.0 : 0.0, 0, false, 1, "-", "true, false", description};
}

NodeParameterSpec tripleParameter(const char* key, double limit, const char* unit, const char* limit_text,
                                  const char* description) {
  return {key, "double[3]", "[0, 0, 0]", 0, 0, false, limit, unit, std::string("finite, each within ±") + limit_text,
          description};
}

NodeParameterSpec listParameter(const char* key, const char* type, const char* unit, const char* allowed,
                                const char* description) {
  return {key, type, "required", 0, 0, false, 0, unit, allowed, description};
}

std::string describeParameterValue(const XmlRpc::XmlRpcValue& v) {
  auto& x = const_cast<XmlRpc::XmlRpcValue&>(v);
  switch (x.getType()) {
    case XmlRpc::XmlRpcValue::TypeDouble: return formatMessage(static_cast<double>(x));
    case XmlRpc::XmlRpcValue::TypeInt: return std::to_string(static_cast<int>(x));
    case XmlRpc::XmlRpcValue::TypeBoolean: return static_cast<bool>(x) ? "true" : "false";
    case XmlRpc::XmlRpcValue::TypeString: return "'" + static_cast<std::string>(x) + "'";
    case XmlRpc::XmlRpcValue::TypeArray: {
      std::string out = "[";
      for (int i = 0; i < x.size(); ++i) out += (i > 0 ? ", " : "") + describeParameterValue(x[i]);
      return out + "]";
    }
    case XmlRpc::XmlRpcValue::TypeStruct: {
      std::string out = "{";
      for (const auto& entry : x) {
        out += (out.size() > 1 ? ", " : "") + entry.first + ": " + describeParameterValue(entry.second);
      }
      return out + "}";
    }
    default: return "(" + std::string(x.valid() ? "a value of another type" : "empty") + ")";
  }
}

YAML::Node parameterTree(const XmlRpc::XmlRpcValue& v) {
  auto& x = const_cast<XmlRpc::XmlRpcValue&>(v);
  switch (x.getType()) {
    case XmlRpc::XmlRpcValue::TypeDouble: return YAML::Node(static_cast<double>(x));  // max_digits10: every bit
    case XmlRpc::XmlRpcValue::TypeInt: return YAML::Node(static_cast<int>(x));
    case XmlRpc::XmlRpcValue::TypeBoolean: return YAML::Node(static_cast<bool>(x));
    case XmlRpc::XmlRpcValue::TypeString: return YAML::Node(static_cast<std::string>(x));
    case XmlRpc::XmlRpcValue::TypeArray: {
      YAML::Node list(YAML::NodeType::Sequence);
      for (int i = 0; i < x.size(); ++i) list.push_back(parameterTree(x[i]));
      return list;
    }
    case XmlRpc::XmlRpcValue::TypeStruct: {
      YAML::Node map(YAML::NodeType::Map);
      for (const auto& entry : x) map[entry.first] = parameterTree(entry.second);
      return map;
    }
    default: return YAML::Node(describeParameterValue(v));  // no number: refused as one by the key's reader
  }
}

std::vector<double> parameterNumbers(const XmlRpc::XmlRpcValue& v, const std::string& key) {
  std::vector<double> out;
  for (int i = 0; i < v.size(); ++i) {
    double x;
    if (!asParameterNumber(v[i], x)) {
      throw ParameterError("parameter '" + key + "' = " + describeParameterValue(v) + ": entry " +
                           std::to_string(i + 1) + " is not a number");
    }
    out.push_back(x);
  }
  return out;
}

NodeParameterReader::NodeParameterReader(const ros::NodeHandle& nh, const std::vector<NodeParameterSpec>& specs)
    : nh_(nh), specs_(specs) {}

const NodeParameterSpec* NodeParameterReader::findSpec(const std::string& key) const {
  for (const auto& s : specs_) {
    if (s.key == key) return &s;
  }
  return nullptr;
}

const NodeParameterSpec& NodeParameterReader::spec(const std::string& key) const {
  const NodeParameterSpec* s = findSpec(key);
  if (s == nullptr) throw std::logic_error("no node parameter '" + key + "'");
  return *s;
}

double checkNumberParameter(const NodeParameterSpec& spec, double x, double max_override) {
  checkParameterValue(asCoreSpec(spec, std::isnan(max_override) ? spec.max_value : max_override), x);
  return x;
}

double NodeParameterReader::number(const std::string& key, double max_override) const {
  XmlRpc::XmlRpcValue v;
  if (!nh_.getParam(key, v)) return spec(key).default_value;
  double x;
  if (!asParameterNumber(v, x)) {
    throw ParameterError("parameter '" + key + "' = " + describeParameterValue(v) + " is not a number");
  }
  return checkNumberParameter(spec(key), x, max_override);
}

bool NodeParameterReader::flag(const std::string& key) const {
  XmlRpc::XmlRpcValue v;
  if (!nh_.getParam(key, v)) return spec(key).default_value != 0.0;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeBoolean) {
    throw ParameterError("parameter '" + key + "' = " + describeParameterValue(v) + " is not true or false");
  }
  return static_cast<bool>(v);
}

std::string NodeParameterReader::text(const std::string& key) const {
  XmlRpc::XmlRpcValue v;
  if (!nh_.getParam(key, v)) return spec(key).default_text;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeString) {
    throw ParameterError("parameter '" + key + "' = " + describeParameterValue(v) + " is not a string");
  }
  return static_cast<std::string>(v);
}

std::string NodeParameterReader::rosName(const std::string& key) const {
  const std::string name = text(key);
  std::string error;
  if (!ros::names::validate(name, error)) {
    throw ParameterError("parameter '" + key + "' = '" + name + "' is not a valid ROS name: " + error);
  }
  return name;
}

std::array<double, 3> NodeParameterReader::triple(const std::string& key) const {
  const NodeParameterSpec& sp = spec(key);
  XmlRpc::XmlRpcValue v;
  std::array<double, 3> out{{0, 0, 0}};
  if (!nh_.getParam(key, v)) return out;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeArray || v.size() != 3) {
    throw ParameterError("parameter '" + key + "' = " + describeParameterValue(v) + " must be a list of 3 numbers");
  }
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!asParameterNumber(v[i], out[k]) || !std::isfinite(out[k]) || std::fabs(out[k]) > sp.max_value) {
      throw ParameterError("parameter '" + key + "' = " + describeParameterValue(v) + ": entry " +
                           std::to_string(i + 1) + " is not a number in the allowed range: " + sp.allowed);
    }
  }
  return out;
}

std::vector<double> NodeParameterReader::numbers(const std::string& key, std::size_t size) const {
  XmlRpc::XmlRpcValue v;
  const std::string wanted = size > 0 ? "a list of " + std::to_string(size) + " numbers" : "a list of numbers";
  if (!nh_.getParam(key, v)) throw ParameterError("parameter '" + key + "' is missing: give " + wanted);
  if (v.getType() != XmlRpc::XmlRpcValue::TypeArray || (size > 0 && std::size_t(v.size()) != size)) {
    throw ParameterError("parameter '" + key + "' = " + describeParameterValue(v) + " must be " + wanted);
  }
  std::vector<double> out = parameterNumbers(v, key);
  for (double x : out) {
    if (!std::isfinite(x)) throw ParameterError("parameter '" + key + "' = " + describeParameterValue(v) + " is not finite");
  }
  return out;
}

std::vector<std::string> NodeParameterReader::texts(const std::string& key) const {
  XmlRpc::XmlRpcValue v;
  if (!nh_.getParam(key, v)) throw ParameterError("parameter '" + key + "' is missing: give a list of names");
  std::vector<std::string> out;
  const bool is_list = v.getType() == XmlRpc::XmlRpcValue::TypeArray && v.size() > 0;
  for (int i = 0; is_list && i < v.size(); ++i) {
    if (v[i].getType() != XmlRpc::XmlRpcValue::TypeString || static_cast<std::string>(v[i]).empty()) break;
    out.push_back(static_cast<std::string>(v[i]));
  }
  if (!is_list || out.size() != std::size_t(v.size())) {
    throw ParameterError("parameter '" + key + "' = " + describeParameterValue(v) +
                         " must be a non-empty list of non-empty strings");
  }
  return out;
}

std::vector<std::string> NodeParameterReader::givenKeys() const {
  std::vector<std::string> names, out;
  nh_.getParamNames(names);
  const std::string ns = nh_.getNamespace() + "/";
  for (const std::string& full : names) {
    if (full.compare(0, ns.size(), ns) == 0) out.push_back(full.substr(ns.size()));
  }
  return out;
}

std::string parameterTableMarkdown(const std::vector<NodeParameterSpec>& specs) {
  std::ostringstream out;
  out << "| parameter | type | default | unit | allowed | meaning |\n|---|---|---|---|---|---|\n";
  for (const auto& s : specs) {
    const bool literal = !s.default_text.empty() && s.default_text != "required";
    out << "| `~" << s.key << "` | " << s.type << " | " << (literal ? "`" + s.default_text + "`" : s.default_text.empty() ? "(empty)" : s.default_text)
        << " | " << s.unit << " | " << s.allowed << " | " << s.description << " |\n";
  }
  return out.str();
}

bool printParametersIfAsked(int argc, char** argv, const std::vector<NodeParameterSpec>& specs) {
  if (argc < 2 || std::string(argv[1]) != "--parameters") return false;
  std::cout << parameterTableMarkdown(specs);
  return true;
}

}  // namespace pneumatic_finger
