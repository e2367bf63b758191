#include "pneumatic_finger/core/csv_fields.hpp"

#include <sstream>

#include "pneumatic_finger/core/parameters.hpp"

namespace pneumatic_finger {

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string field;
  while (std::getline(s, field, ',')) {
    const auto a = field.find_first_not_of(" \t\r");
    const auto b = field.find_last_not_of(" \t\r");
    out.push_back(a == std::string::npos ? "" : field.substr(a, b - a + 1));
  }
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

std::vector<std::string> splitCsvHeader(const std::string& line, const std::string& at) {
  std::vector<std::string> fields = splitCsv(line);
  if (fields.size() != 1) return fields;
  for (const char* separator : {";", "\t"}) {
    if (line.find(separator) == std::string::npos) continue;
    throw ParameterError(at + "the header '" + fields[0] + "' is separated by " +
                         (separator[0] == ';' ? "';'" : "tabs") + ": the package reads comma-separated values with a "
                         "decimal point (export the sheet as CSV with ',' between fields and '.' in numbers)");
  }
  return fields;
}

}  // namespace pneumatic_finger
