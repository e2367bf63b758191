// What was measured, read from a CSV: a gauge_pa column and any of the joint angles, a tip angle or a tip position
// (calibration.hpp, Measurement), refused with the file, the line and the column named when malformed.
#include "pneumatic_finger/core/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>

namespace pneumatic_finger {

double Measurement::averageOuterJoints() const {
  if (!std::isnan(given_average_rad)) return given_average_rad;
  double sum = 0.0;
  for (std::size_t k = 1; k < joint_rad.size(); ++k) sum += joint_rad[k];
  return sum / static_cast<double>(joint_rad.size() - 1);
}

namespace {

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

std::string where(const std::string& origin, int line) { return origin + ":" + std::to_string(line) + ": "; }

}  // namespace

namespace {

// Where each measured quantity stands in a measurement CSV (-1: absent).
struct CsvColumns {
  int gauge = -1, average = -1, tip_angle = -1, tip_x = -1, tip_y = -1;
  std::vector<int> joints;
};

// The header's columns. @throws ParameterError naming the line and what the header lacks.
CsvColumns readHeader(const std::vector<std::string>& header, const std::string& average_column,
                      const std::string& at) {
  CsvColumns c;
  for (std::size_t i = 0; i < header.size(); ++i) {
    const int k = static_cast<int>(i);
    if (header[i] == "gauge_pa") c.gauge = k;
    // A segment's bend angle (the angle between its base and its tip, as bending tests report it) is the tip's
    // direction Theta_N: the same number under another name.
    if (header[i] == "tip_angle_rad" || header[i] == "bend_angle_rad") {
      if (c.tip_angle >= 0) throw ParameterError(at + "header has both tip_angle_rad and bend_angle_rad; give one");
      c.tip_angle = k;
    }
    if (header[i] == "tip_x_m") c.tip_x = k;
    if (header[i] == "tip_y_m") c.tip_y = k;
    if (!average_column.empty() && header[i] == average_column) c.average = k;
  }
  if (!average_column.empty() && c.average < 0) throw ParameterError(at + "header has no '" + average_column + "' column");
  if (c.gauge < 0) throw ParameterError(at + "header has no 'gauge_pa' column");
  for (int k = 1;; ++k) {
    const auto it = std::find(header.begin(), header.end(), "joint_" + std::to_string(k) + "_rad");
    if (it == header.end()) break;
    c.joints.push_back(static_cast<int>(it - header.begin()));
  }
  if (c.joints.size() == 1) {
    throw ParameterError(at + "header has joint_1_rad alone; give joint_1_rad, joint_2_rad, ... (at least two joints), "
                         "or none");
  }
  if ((c.tip_x < 0) != (c.tip_y < 0)) {
    throw ParameterError(at + "header has " + (c.tip_x < 0 ? "tip_y_m" : "tip_x_m") + " without " +
                         (c.tip_x < 0 ? "tip_x_m" : "tip_y_m") + "; a tip position needs both");
  }
  if (c.joints.empty() && c.tip_angle < 0 && c.tip_x < 0) {
    throw ParameterError(at + "header has nothing measured: give joint_1_rad, joint_2_rad, ... (joint angles), "
                         "tip_angle_rad, or tip_x_m,tip_y_m (the tip in the finger's frame)");
  }
  if (c.average >= 0 && c.joints.empty()) {
    throw ParameterError(at + "column '" + average_column +
                         "' is an average of joints 2..N, but the header has no joint columns");
  }
  return c;
}

// One data row. @throws ParameterError naming the line, the column and the field that is not a finite number.
Measurement readRow(const std::vector<std::string>& fields, const std::vector<std::string>& header,
                    const CsvColumns& c, int line, const std::string& at) {
  if (fields.size() != header.size()) {
    throw ParameterError(at + "has " + std::to_string(fields.size()) + " fields, the header " +
                         std::to_string(header.size()));
  }
  auto number_at = [&](int column) {
    const std::string& f = fields[static_cast<std::size_t>(column)];
    char* end = nullptr;
    const double v = std::strtod(f.c_str(), &end);
    if (f.empty() || *end != '\0' || !std::isfinite(v)) {
      throw ParameterError(at + "'" + f + "' in column " + header[static_cast<std::size_t>(column)] +
                           " is not a finite number");
    }
    return v;
  };
  Measurement m;
  m.line = line;
  m.gauge_pa = number_at(c.gauge);
  if (m.gauge_pa < 0) throw ParameterError(at + "gauge_pa is negative");
  for (int column : c.joints) m.joint_rad.push_back(number_at(column));
  if (c.average >= 0) m.given_average_rad = number_at(c.average);
  if (c.tip_angle >= 0) m.tip_angle_rad = number_at(c.tip_angle);
  if (c.tip_x >= 0) {
    m.tip_x_m = number_at(c.tip_x);
    m.tip_y_m = number_at(c.tip_y);
  }
  return m;
}

}  // namespace

std::vector<Measurement> parseMeasurementsCsv(const std::string& text, const std::string& origin,
                                              std::size_t min_rows, const std::string& average_column) {
  std::stringstream in(text);
  std::string line;
  int number = 0;
  std::vector<std::string> header;
  CsvColumns columns;
  std::vector<Measurement> rows;
  while (std::getline(in, line)) {
    ++number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::vector<std::string> fields = splitCsv(line);
    if (header.empty()) {
      header = fields;
      columns = readHeader(header, average_column, where(origin, number));
    } else {
      rows.push_back(readRow(fields, header, columns, number, where(origin, number)));
    }
  }
  if (header.empty()) throw ParameterError(origin + ": no header line");
  if (rows.size() < min_rows) {
    throw ParameterError(where(origin, number) + "only " + std::to_string(rows.size()) + " data rows; at least " +
                         std::to_string(min_rows) + " are needed");
  }
  return rows;
}

std::vector<Measurement> readMeasurementsCsv(const std::string& path, std::size_t min_rows,
                                             const std::string& average_column) {
  std::ifstream in(path);
  if (!in) throw ParameterError("cannot read measurement file '" + path + "'");
  std::stringstream text;
  text << in.rdbuf();
  return parseMeasurementsCsv(text.str(), path, min_rows, average_column);
}

}  // namespace pneumatic_finger
