// The package's CSV files (measurements, coupon tests): one line's comma-separated fields, trimmed.
#pragma once

#include <string>
#include <vector>

namespace pneumatic_finger {

/// The fields of one CSV line, each trimmed of spaces, tabs and a carriage return; a trailing comma gives an empty
/// last field.
std::vector<std::string> splitCsv(const std::string& line);

}  // namespace pneumatic_finger
