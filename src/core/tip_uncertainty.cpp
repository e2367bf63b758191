#include "pneumatic_finger/core/tip_uncertainty.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "pneumatic_finger/core/parameters.hpp"
#include "yaml_node.hpp"

namespace pneumatic_finger {

TipUncertainty::At TipUncertainty::at(double pressure_pa) const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (empty() || std::isnan(pressure_pa)) return {nan, nan, false};
  if (pressure_pa <= 0.0) return {0.0, 0.0, false};
  const std::size_t last = gauge_pa.size() - 1;
  if (pressure_pa > gauge_pa[last]) {
    const double scale = pressure_pa / gauge_pa[last];
    return {tip_angle_rad[last] * scale, tip_position_m[last] * scale, true};
  }
  // Below the first calibrated pressure the calibration saw nothing: its bar, flagged (it once shrank to 0 here).
  if (pressure_pa < gauge_pa[0]) return {tip_angle_rad[0], tip_position_m[0], true};
  // Between two calibrated points: linear.
  double p0 = gauge_pa[0], a0 = tip_angle_rad[0], x0 = tip_position_m[0];
  for (std::size_t i = 0; i <= last; ++i) {
    const double p1 = gauge_pa[i];
    if (pressure_pa <= p1) {
      const double t = (pressure_pa - p0) / (p1 - p0);
      return {a0 + t * (tip_angle_rad[i] - a0), x0 + t * (tip_position_m[i] - x0), false};
    }
    p0 = p1;
    a0 = tip_angle_rad[i];
    x0 = tip_position_m[i];
  }
  return {tip_angle_rad[last], tip_position_m[last], false};
}

TipUncertainty TipUncertainty::fromLists(const std::vector<double>& gauge_pa, const std::vector<double>& tip_angle_rad,
                                         const std::vector<double>& tip_position_m, const std::string& origin) {
  const std::string where = origin + ": " + kTipUncertaintyKey + ": ";
  if (gauge_pa.size() != tip_angle_rad.size() || gauge_pa.size() != tip_position_m.size()) {
    throw ParameterError(where + "gauge_pa, tip_angle_rad and tip_position_m must have the same length (" +
                         std::to_string(gauge_pa.size()) + ", " + std::to_string(tip_angle_rad.size()) + ", " +
                         std::to_string(tip_position_m.size()) + ")");
  }
  for (std::size_t i = 0; i < gauge_pa.size(); ++i) {
    const std::string entry = " (entry " + std::to_string(i + 1) + ")";
    if (!std::isfinite(gauge_pa[i]) || gauge_pa[i] <= 0.0 || (i > 0 && gauge_pa[i] <= gauge_pa[i - 1])) {
      throw ParameterError(where + "gauge_pa = " + formatMessage(gauge_pa[i]) + entry +
                           " must be finite, > 0 and ascending");
    }
    // NaN: not measured. Tip positions from a camera give no angle; a bar needs at least one of the two.
    if (tip_angle_rad[i] < 0.0 || std::isinf(tip_angle_rad[i])) {
      throw ParameterError(where + "tip_angle_rad = " + formatMessage(tip_angle_rad[i]) + entry +
                           " must be >= 0 and finite (or .nan: not measured)");
    }
    if (std::isnan(tip_angle_rad[i]) && std::isnan(tip_position_m[i])) {
      throw ParameterError(where + "entry " + std::to_string(i + 1) +
                           " has neither tip_angle_rad nor tip_position_m: give at least one");
    }
    if (tip_position_m[i] < 0.0 || std::isinf(tip_position_m[i])) {
      throw ParameterError(where + "tip_position_m = " + formatMessage(tip_position_m[i]) + entry +
                           " must be >= 0 and finite (or .nan: not measured)");
    }
  }
  return {gauge_pa, tip_angle_rad, tip_position_m};
}

TipUncertainty tipUncertaintyFromYamlNode(const YAML::Node& root, const std::string& origin) {
  if (!root.IsMap() || !root[kTipUncertaintyKey]) return {};
  const YAML::Node node = root[kTipUncertaintyKey];
  if (!node.IsMap()) throw ParameterError(origin + ": " + kTipUncertaintyKey + " must be a mapping");
  auto list = [&](const char* key) {
    std::vector<double> out;
    const YAML::Node l = node[key];
    if (!l || !l.IsSequence()) {
      throw ParameterError(origin + ": " + kTipUncertaintyKey + ": '" + key + "' must be a list of numbers");
    }
    for (const auto& e : l) {
      try {
        out.push_back(e.as<double>());
      } catch (const YAML::Exception&) {
        throw ParameterError(origin + ": " + kTipUncertaintyKey + ": '" + key + "' has '" + e.Scalar() +
                             "', not a number");
      }
    }
    return out;
  };
  for (const auto& item : node) {
    const std::string key = item.first.as<std::string>();
    if (key != "gauge_pa" && key != "tip_angle_rad" && key != "tip_position_m") {
      throw ParameterError(origin + ": " + kTipUncertaintyKey + ": unknown key '" + key +
                           "' (known: gauge_pa, tip_angle_rad, tip_position_m)");
    }
  }
  // In the file's order, so that the first list at fault is the one named (arguments have no order of evaluation).
  const std::vector<double> gauge_pa = list("gauge_pa");
  const std::vector<double> tip_angle_rad = list("tip_angle_rad");
  return TipUncertainty::fromLists(gauge_pa, tip_angle_rad, list("tip_position_m"), origin);
}

std::string tipUncertaintyToYaml(const TipUncertainty& u) {
  std::ostringstream out;
  auto list = [&out](const std::vector<double>& v) {
    out << "[";
    for (std::size_t i = 0; i < v.size(); ++i) out << (i ? ", " : "") << formatYamlNumber(v[i]);
    out << "]\n";
  };
  out << "# How far to trust the tip (written by finger_calibrate; docs/ACCURACY.md): at each calibrated gauge pressure\n"
      << "# (Pa), the largest of the fit's error, the leave-one-out error and the fit's residual scatter, for the tip\n"
      << "# angle (rad) and the tip position (m). finger_node interpolates it linearly in pressure between them and\n"
      << "# flags pressures outside them (below the first: its bar; above the last: that bar scaled by the pressure).\n"
      << kTipUncertaintyKey << ":\n  gauge_pa: ";
  list(u.gauge_pa);
  out << "  tip_angle_rad: ";
  list(u.tip_angle_rad);
  out << "  tip_position_m: ";
  list(u.tip_position_m);
  return out.str();
}

}  // namespace pneumatic_finger
