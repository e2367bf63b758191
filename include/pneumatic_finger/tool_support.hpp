// Small pieces shared by the command-line tools (finger_model, finger_calibrate): where the package's default
// parameter file is, and reading --config/--set into validated parameters. ROS-free, like the core.
#pragma once

#include <string>
#include <vector>

#include "pneumatic_finger/parameters.hpp"

namespace pneumatic_finger {

/// The package's default parameter file (config/finger.yaml): the source tree's copy when built from source,
/// else the installed share folder next to the executable.
std::string defaultParameterFile(const char* argv0);

/// Loads @p config_path (or the default file when empty), applies the KEY=VALUE @p assignments on top, validates.
/// @throws ParameterError naming what was wrong
FingerParameters loadToolParameters(const std::string& config_path, const std::vector<std::string>& assignments,
                                    const char* argv0);

/// Parses a finite double for a command-line option. @throws ParameterError naming @p option and @p text.
double parseFiniteOption(const std::string& option, const std::string& text);

}  // namespace pneumatic_finger
