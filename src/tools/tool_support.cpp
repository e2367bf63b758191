#include "pneumatic_finger/tools/tool_support.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pneumatic_finger {

namespace {

// The running executable's folder, from /proc (argv[0] may be a bare name found on PATH).
std::string executableDirectory() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return ".";
  const std::string exe(buf, static_cast<std::size_t>(n));
  return exe.substr(0, exe.rfind('/'));
}

}  // namespace

std::string packageShareDirectory() {
  // Installed (or devel) layout: <prefix>/lib/pneumatic_finger/<tool> beside <prefix>/share/pneumatic_finger/.
  // The installed copy wins over the source tree, so an installed tool never reads a checkout it happens to sit next to.
  const std::string share = executableDirectory() + "/../../share/pneumatic_finger";
  if (std::ifstream(share + "/config/finger.yaml").good()) return share;
  return PNEUMATIC_FINGER_SOURCE_DIR;
}

std::string defaultParameterFile() { return packageShareDirectory() + "/config/finger.yaml"; }

CLI::Option* addRepeatedOption(CLI::App& app, const std::string& name, std::vector<std::string>& values,
                               const std::string& description, const std::string& value_name) {
  return app.add_option(name, values, description)
      ->type_name(value_name)
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false);
}

void ParameterOptions::addTo(CLI::App& app) {
  app.add_option("--config", config, "actuator parameter file (YAML); default: the package's config/finger.yaml");
  addRepeatedOption(app, "--set", assignments,
                    "KEY=VALUE on top of the file (repeatable); `finger_model --parameters` lists keys", "KEY=VALUE");
}

RawParameterMap ParameterOptions::loadRaw() const {
  RawParameterMap raw;
  loadRawParametersFromYamlFile(config.empty() ? defaultParameterFile() : config, raw);
  for (const auto& a : assignments) parseParameterAssignment(a, raw);
  return raw;
}

FingerParameters ParameterOptions::load() const { return FingerParameters::fromRaw(loadRaw()); }

PressureRange ParameterOptions::loadRange(const std::string& max_gauge_text) const {
  RawParameterMap raw;
  PressureRange range;
  loadRawParametersFromYamlFile(config.empty() ? defaultParameterFile() : config, raw, nullptr, &range);
  return max_gauge_text.empty() ? range : range.withTop(parseFiniteOption("--max-gauge-pa", max_gauge_text));
}

int runTool(const char* tool, CLI::App& app, int argc, char** argv, const std::function<int()>& body) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    std::cerr << tool << ": error: " << e.what() << "\n";
    return 2;
  }
  try {
    return body();
  } catch (const ParameterError& e) {
    std::cerr << tool << ": error: " << e.what() << "\n";
    return 2;
  }
}

double parseNumberOption(const std::string& option, const std::string& text) {
  const std::optional<double> v = readNumber(text);
  if (!v) throw ParameterError(option + ": '" + text + "' is not a number");
  return *v;
}

double parseFiniteOption(const std::string& option, const std::string& text) {
  const double v = parseNumberOption(option, text);
  if (!std::isfinite(v)) throw ParameterError(option + ": " + text + " is not a finite number");
  return v;
}

std::vector<std::string> splitFields(const std::string& text, char separator) {
  std::vector<std::string> out;
  if (text.empty()) return out;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, separator)) out.push_back(item);
  if (text.back() == separator) out.emplace_back();
  return out;
}

}  // namespace pneumatic_finger
