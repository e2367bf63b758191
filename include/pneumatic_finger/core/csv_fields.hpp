// The package's CSV files (measurements, coupon tests): one line's comma-separated fields, trimmed.
#pragma once

#include <string>
#include <vector>

namespace pneumatic_finger {

/// The fields of one CSV line, each trimmed of spaces, tabs and a carriage return; a trailing comma gives an empty
/// last field.
std::vector<std::string> splitCsv(const std::string& line);

/// A header line as the package reads it: its comma-separated fields. @throws ParameterError naming @p at when the
/// line is one field separated by ';' or tabs (a spreadsheet's export in a locale with a decimal comma), with the fix.
std::vector<std::string> splitCsvHeader(const std::string& line, const std::string& at);

}  // namespace pneumatic_finger
