// What the command-line tools (finger_model, finger_calibrate, finger_urdf) share: one argument parser (CLI11) with
// the same --config/--set options and the same error convention, and where the package's files are. ROS-free.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/pressure_range.hpp"

namespace pneumatic_finger {

/// The folder of the package's shared files (config/, data/, urdf/): the install space's
/// <prefix>/share/pneumatic_finger when the running executable is installed, else the source tree it was built from.
std::string packageShareDirectory();

/// The package's default parameter file, packageShareDirectory() + "/config/finger.yaml".
std::string defaultParameterFile();

/// An option that takes one value per occurrence and is repeated for several (--gauge-pa 1 --gauge-pa 2): the help
/// shows "--NAME @p value_name", and a second value after one occurrence is refused.
CLI::Option* addRepeatedOption(CLI::App& app, const std::string& name, std::vector<std::string>& values,
                               const std::string& description, const std::string& value_name);

/// The actuator options every tool takes: --config FILE.yaml and repeated --set KEY=VALUE.
struct ParameterOptions {
  std::string config;
  std::vector<std::string> assignments;

  /// Adds --config and --set to @p app.
  void addTo(CLI::App& app);

  /// Loads the config (or the default file), applies the assignments on top, validates.
  /// @throws ParameterError naming what was wrong
  FingerParameters load() const;

  /// The same keys before validation (calibrationBase validates them under the law it fits).
  /// @throws ParameterError naming the file or the assignment
  RawParameterMap loadRaw() const;

  /// The file's range (max_gauge_pa, validated_max_gauge_pa; the defaults where it has none), as every interface
  /// reads it; @p max_gauge_text, a tool's --max-gauge-pa when given, replaces the top (the validated range no higher).
  /// @throws ParameterError naming the file or the option
  PressureRange loadRange(const std::string& max_gauge_text = "") const;
};

/// Parses the command line with @p app and runs @p body. The convention of every tool: --help prints the usage and
/// exits 0; a bad argument or a ParameterError prints one line "<tool>: error: <what>" on stderr and exits 2.
int runTool(const char* tool, CLI::App& app, int argc, char** argv, const std::function<int()>& body);

/// Parses a finite double for a command-line option. @throws ParameterError naming @p option and @p text.
double parseFiniteOption(const std::string& option, const std::string& text);
/// A number, finite or not (NaN and inf are the caller's to refuse, in the input's own words).
/// @throws ParameterError naming @p option for text that is no number
double parseNumberOption(const std::string& option, const std::string& text);

/// Splits "A,B,C" (or with another @p separator) into its fields; an empty text gives no field.
std::vector<std::string> splitFields(const std::string& text, char separator = ',');

}  // namespace pneumatic_finger
