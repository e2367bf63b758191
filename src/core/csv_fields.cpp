#include "pneumatic_finger/core/csv_fields.hpp"

#include <sstream>

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

}  // namespace pneumatic_finger
