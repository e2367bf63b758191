#include "pneumatic_finger/tool_support.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "pneumatic_finger/yaml_parameters.hpp"

#ifndef PNEUMATIC_FINGER_SOURCE_DIR
#define PNEUMATIC_FINGER_SOURCE_DIR ""
#endif

namespace pneumatic_finger {

std::string defaultParameterFile(const char* argv0) {
  const std::string source = std::string(PNEUMATIC_FINGER_SOURCE_DIR) + "/config/finger.yaml";
  if (std::ifstream(source).good()) return source;
  // Installed layout: <prefix>/lib/pneumatic_finger/<tool> and <prefix>/share/pneumatic_finger/config/.
  std::string exe = argv0 ? argv0 : "";
  const auto slash = exe.rfind('/');
  const std::string dir = slash == std::string::npos ? "." : exe.substr(0, slash);
  return dir + "/../../share/pneumatic_finger/config/finger.yaml";
}

FingerParameters loadToolParameters(const std::string& config_path, const std::vector<std::string>& assignments,
                                    const char* argv0) {
  RawParameterMap raw;
  loadRawParametersFromYamlFile(config_path.empty() ? defaultParameterFile(argv0) : config_path, raw);
  for (const auto& a : assignments) parseParameterAssignment(a, raw);
  return FingerParameters::fromRaw(raw);
}

double parseFiniteOption(const std::string& option, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end == nullptr || *end != '\0') {
    throw ParameterError(option + ": '" + text + "' is not a number");
  }
  if (!std::isfinite(v)) throw ParameterError(option + ": " + text + " is not a finite number");
  return v;
}

}  // namespace pneumatic_finger
