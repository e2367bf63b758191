#include "pneumatic_finger/core/calibration_error.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "pneumatic_finger/core/parameters.hpp"
#include "yaml_node.hpp"

namespace pneumatic_finger {

namespace {

std::string degrees(double rad) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f deg", rad * 180.0 / M_PI);
  return b;
}

// A number of the entry: finite and >= 0. @throws ParameterError naming @p origin and the key
double entryNumber(const YAML::Node& node, const char* key, const std::string& origin) {
  const std::string where = origin + ": " + kCalibrationErrorKey + ": '" + key + "'";
  if (!node[key] || !node[key].IsScalar()) throw ParameterError(where + " is missing");
  double v = 0.0;
  try {
    v = node[key].as<double>();
  } catch (const YAML::Exception&) {
    throw ParameterError(where + " = '" + node[key].Scalar() + "' is not a number");
  }
  if (!(v >= 0.0) || std::isinf(v)) throw ParameterError(where + " = " + formatMessage(v) + " must be finite and >= 0");
  return v;
}

}  // namespace

std::string CalibrationError::describe() const {
  if (empty()) return "none (no calibration_error in the parameter file)";
  return "held out (" + compared + "): " + degrees(held_out_largest_rad) + " largest (at " +
         formatMessage(largest_at_gauge_pa) + " Pa), " + degrees(held_out_rms_rad) + " rms; " +
         (follows_data ? std::string("follows its data")
                       : "does NOT follow its data: " + std::to_string(missed_rows) + " rows missed");
}

CalibrationError calibrationErrorFromYamlNode(const YAML::Node& root, const std::string& origin) {
  if (!root.IsMap() || !root[kCalibrationErrorKey]) return {};
  const YAML::Node node = root[kCalibrationErrorKey];
  if (!node.IsMap()) throw ParameterError(origin + ": " + kCalibrationErrorKey + " must be a mapping");
  for (const auto& item : node) {
    const std::string key = item.first.as<std::string>();
    if (key != "compared" && key != "held_out_rms_rad" && key != "held_out_largest_rad" &&
        key != "largest_at_gauge_pa" && key != "missed_rows" && key != "follows_data") {
      throw ParameterError(origin + ": " + kCalibrationErrorKey + ": unknown key '" + key + "' (known: compared, "
                           "held_out_rms_rad, held_out_largest_rad, largest_at_gauge_pa, missed_rows, follows_data)");
    }
  }
  CalibrationError e;
  e.compared = node["compared"] && node["compared"].IsScalar() ? node["compared"].Scalar() : "";
  if (e.compared.empty()) throw ParameterError(origin + ": " + kCalibrationErrorKey + ": 'compared' is missing");
  e.held_out_rms_rad = entryNumber(node, "held_out_rms_rad", origin);
  e.held_out_largest_rad = entryNumber(node, "held_out_largest_rad", origin);
  e.largest_at_gauge_pa = entryNumber(node, "largest_at_gauge_pa", origin);
  e.missed_rows = static_cast<int>(entryNumber(node, "missed_rows", origin));
  try {
    e.follows_data = node["follows_data"].as<bool>();
  } catch (const YAML::Exception&) {
    throw ParameterError(origin + ": " + kCalibrationErrorKey + ": 'follows_data' must be true or false");
  }
  return e;
}

std::string calibrationErrorToYaml(const CalibrationError& e) {
  if (e.empty()) return "";
  std::ostringstream out;
  out << "# How well the calibration followed its data (written by finger_calibrate; docs/CALIBRATE.md): the bends\n"
      << "# it predicted for rows it was not fitted to (leave-one-out), rms and largest (rad), the rows it missed\n"
      << "# beyond the follow bar, and whether it follows its data. finger_node's diagnostics report it.\n"
      << kCalibrationErrorKey << ":\n"
      << "  compared: " << e.compared << "\n"
      << "  held_out_rms_rad: " << formatYamlNumber(e.held_out_rms_rad) << "\n"
      << "  held_out_largest_rad: " << formatYamlNumber(e.held_out_largest_rad) << "\n"
      << "  largest_at_gauge_pa: " << formatYamlNumber(e.largest_at_gauge_pa) << "\n"
      << "  missed_rows: " << e.missed_rows << "\n"
      << "  follows_data: " << (e.follows_data ? "true" : "false") << "\n";
  return out.str();
}

}  // namespace pneumatic_finger
