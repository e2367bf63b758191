// What was measured, read from a CSV: a gauge_pa column and any of the joint angles, a tip angle or a tip position
// (calibration.hpp, Measurement), refused with the file, the line and the column named when malformed.
#include "pneumatic_finger/calibration/calibration.hpp"

#include "pneumatic_finger/core/csv_fields.hpp"
#include "pneumatic_finger/core/units.hpp"

#include <algorithm>
#include <cctype>
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

std::string where(const std::string& origin, int line) { return origin + ":" + std::to_string(line) + ": "; }

// The columns calibration reads besides the joints (and the average column, named by the caller).
constexpr const char* kMeasuredColumns[] = {"gauge_pa",        "supplied_volume_m3", "tip_angle_rad",
                                           "bend_angle_rad",  "chord_angle_rad",    "tip_x_m",
                                           "tip_y_m",         "blocked_tip_force_n"};

// "joint_<k>" for a whole number k: the stem of a joint's column, whatever its unit.
bool isJointStem(const std::string& stem) {
  return stem.rfind("joint_", 0) == 0 && stem.size() > 6 && stem.find_first_not_of("0123456789", 6) == std::string::npos;
}

// A column name calibration reads (the average column aside).
bool isMeasuredColumn(const std::string& name) {
  for (const char* known : kMeasuredColumns) {
    if (name == known) return true;
  }
  return name.size() > 4 && name.compare(name.size() - 4, 4, "_rad") == 0 && isJointStem(name.substr(0, name.size() - 4));
}

}  // namespace

namespace {

// Where each measured quantity stands in a measurement CSV (-1: absent), and the columns calibration does not read.
struct CsvColumns {
  int gauge = -1, volume = -1, average = -1, tip_angle = -1, chord = -1, tip_x = -1, tip_y = -1, force = -1;
  std::vector<int> joints;
  std::vector<std::string> unused;
};

// What calibration reads, for messages about a column it does not.
constexpr const char* kKnownColumns =
    "gauge_pa, supplied_volume_m3, joint_1_rad..joint_N_rad, tip_angle_rad (or bend_angle_rad), chord_angle_rad, "
    "tip_x_m,tip_y_m, blocked_tip_force_n";

// A column calibration does not read that looks like one of ours under another unit ("tip_x_mm" for tip_x_m,
// "tip_angle_deg" for tip_angle_rad, "joint_2_deg" for joint_2_rad): what it may have meant, or empty.
std::string meantColumn(const std::string& column) {
  const auto cut = column.rfind('_');
  const std::string stem = cut == std::string::npos ? column : column.substr(0, cut);
  for (const char* known : kMeasuredColumns) {
    const std::string k = known;
    if (stem == k.substr(0, k.rfind('_'))) return k;
  }
  return isJointStem(stem) ? stem + "_rad" : std::string();
}

// The columns calibration does not read, named: each that looks like one of ours under another unit with what it
// may have meant, the others in one line. Extra columns are common (a source's own units, notes), so they are
// named, not refused.
std::vector<std::string> unusedColumnNotes(const std::vector<std::string>& unused) {
  std::vector<std::string> notes;
  std::string others;
  for (const std::string& column : unused) {
    const std::string meant = meantColumn(column);
    if (!meant.empty()) {
      notes.push_back("column '" + column + "' is not read: did you mean '" + meant + "'? (SI units: Pa, rad, m)");
    } else {
      others += (others.empty() ? "" : ", ") + column;
    }
  }
  if (!others.empty()) {
    notes.push_back("columns not read: " + others + " (calibration reads " + kKnownColumns + ")");
  }
  return notes;
}

// What the header probably meant, for the message that refuses it: another separator, or a pressure in another unit.
std::string headerHint(const std::vector<std::string>& header) {
  for (const std::string& name : header) {
    if (name.find(';') != std::string::npos || name.find('\t') != std::string::npos) {
      return "; the header reads as one column '" + name + "': separate the columns with commas";
    }
  }
  for (const std::string& name : header) {
    std::string lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char ch) { return std::tolower(ch); });
    if (lower.find("pressure") != std::string::npos || lower.find("kpa") != std::string::npos ||
        lower.find("psi") != std::string::npos || lower.find("bar") != std::string::npos) {
      return "; column '" + name + "' looks like a pressure: give it as gauge_pa, gauge pressure in Pa (1 kPa = 1000 "
             "Pa, 1 bar = 100000 Pa, 1 psi = 6894.76 Pa)";
    }
  }
  return "";
}

// The header's columns. @throws ParameterError naming the line and what the header lacks.
CsvColumns readHeader(const std::vector<std::string>& header, const std::string& average_column,
                      const std::string& at) {
  CsvColumns c;
  for (std::size_t i = 0; i < header.size(); ++i) {
    const int k = static_cast<int>(i);
    if (!isMeasuredColumn(header[i]) && header[i] != average_column) c.unused.push_back(header[i]);
    if (header[i] == "gauge_pa") c.gauge = k;
    if (header[i] == "supplied_volume_m3") c.volume = k;
    // A segment's bend angle (the angle between its base and its tip, as bending tests report it) is the tip's
    // direction Theta_N: the same number under another name.
    if (header[i] == "tip_angle_rad" || header[i] == "bend_angle_rad") {
      if (c.tip_angle >= 0) throw ParameterError(at + "header has both tip_angle_rad and bend_angle_rad; give one");
      c.tip_angle = k;
    }
    if (header[i] == "chord_angle_rad") c.chord = k;
    if (header[i] == "blocked_tip_force_n") c.force = k;
    if (header[i] == "tip_x_m") c.tip_x = k;
    if (header[i] == "tip_y_m") c.tip_y = k;
    if (!average_column.empty() && header[i] == average_column) c.average = k;
  }
  if (!average_column.empty() && c.average < 0) throw ParameterError(at + "header has no '" + average_column + "' column");
  if (c.gauge < 0 && c.volume < 0) {
    throw ParameterError(at + "header has no 'gauge_pa' column (nor 'supplied_volume_m3', for a finger set by volume)" +
                         headerHint(header));
  }
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
  if (c.joints.empty() && c.tip_angle < 0 && c.chord < 0 && c.tip_x < 0 && c.force < 0) {
    std::string notes;
    for (const std::string& note : unusedColumnNotes(c.unused)) notes += "; " + note;
    throw ParameterError(at + "header has nothing measured: give joint_1_rad, joint_2_rad, ... (joint angles), "
                         "tip_angle_rad, chord_angle_rad (base to tip), tip_x_m,tip_y_m (the tip in the finger's "
                         "frame), or blocked_tip_force_n" + notes);
  }
  if (c.average >= 0 && c.joints.empty()) {
    throw ParameterError(at + "column '" + average_column +
                         "' is an average of joints 2..N, but the header has no joint columns");
  }
  return c;
}

// One data row from its numbers: @p number_at(column) gives the value in a column, or throws naming it.
Measurement measurementFrom(const std::function<double(int)>& number_at, const CsvColumns& c, int line,
                            const std::string& at) {
  Measurement m;
  m.line = line;
  m.gauge_pa = c.gauge >= 0 ? number_at(c.gauge) : std::numeric_limits<double>::quiet_NaN();
  if (m.gauge_pa < 0) throw ParameterError(at + "gauge_pa is negative");
  if (c.volume >= 0) m.supplied_volume_m3 = number_at(c.volume);
  for (int column : c.joints) m.joint_rad.push_back(number_at(column));
  if (c.average >= 0) m.given_average_rad = number_at(c.average);
  if (c.tip_angle >= 0) m.tip_angle_rad = number_at(c.tip_angle);
  if (c.chord >= 0) m.chord_angle_rad = number_at(c.chord);
  if (c.force >= 0) m.blocked_tip_force_n = number_at(c.force);
  if (c.tip_x >= 0) {
    m.tip_x_m = number_at(c.tip_x);
    m.tip_y_m = number_at(c.tip_y);
  }
  return m;
}

// One CSV data row. @throws ParameterError naming the line, the column and the field that is not a finite number.
Measurement readRow(const std::vector<std::string>& fields, const std::vector<std::string>& header,
                    const CsvColumns& c, int line, const std::string& at) {
  if (fields.size() != header.size()) {
    throw ParameterError(at + "has " + std::to_string(fields.size()) + " fields, the header " +
                         std::to_string(header.size()));
  }
  return measurementFrom(
      [&](int column) {
        const std::string& f = fields[static_cast<std::size_t>(column)];
        const std::optional<double> v = readNumber(f);
        if (!v || !std::isfinite(*v)) {
          throw ParameterError(at + "'" + f + "' in column " + header[static_cast<std::size_t>(column)] +
                               " is not a finite number");
        }
        return *v;
      },
      c, line, at);
}

void requireRows(const MeasurementSet& set, std::size_t min_rows, const std::string& at) {
  if (set.rows.size() < min_rows) {
    throw ParameterError(at + "only " + std::to_string(set.rows.size()) + " data rows; at least " +
                         std::to_string(min_rows) + " are needed");
  }
}

MeasurementSet withNotes(const CsvColumns& columns) {
  MeasurementSet set;
  set.notes = unusedColumnNotes(columns.unused);
  return set;
}

}  // namespace

void driveByVolume(std::vector<Measurement>& data, bool by_volume) {
  for (Measurement& m : data) {
    if (m.forceOnly()) {  // a finger held straight is set by its pressure, whatever drives the free one
      if (!m.hasGauge()) throw ParameterError(m.where() + ": blocked_tip_force_n without gauge_pa, its pressure");
      m.driven_by_volume = false;
      continue;
    }
    if (by_volume ? !m.hasSuppliedVolume() : !m.hasGauge()) {
      throw ParameterError(m.where() + ": no " +
                           (by_volume ? "supplied_volume_m3 to drive the finger by volume"
                                      : "gauge_pa to drive the finger by pressure (drive it by volume, or give the "
                                        "column)"));
    }
    m.driven_by_volume = by_volume;
  }
}

bool parseDrive(const std::string& name) {
  if (name == "pressure" || name == "volume") return name == "volume";
  throw ParameterError("unknown drive '" + name + "'; known: pressure (rows set by gauge_pa), volume (rows set by "
                       "supplied_volume_m3)");
}

MeasurementSet parseMeasurementSet(const std::string& text, const std::string& origin, std::size_t min_rows,
                                   const std::string& average_column) {
  std::stringstream in(text);
  std::string line;
  int number = 0;
  std::vector<std::string> header;
  CsvColumns columns;
  MeasurementSet set;
  while (std::getline(in, line)) {
    ++number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::vector<std::string> fields =
        header.empty() ? splitCsvHeader(line, where(origin, number)) : splitCsv(line);
    if (header.empty()) {
      header = fields;
      columns = readHeader(header, average_column, where(origin, number));
      set = withNotes(columns);
    } else {
      set.rows.push_back(readRow(fields, header, columns, number, where(origin, number)));
    }
  }
  if (header.empty()) throw ParameterError(origin + ": no header line");
  requireRows(set, min_rows, where(origin, number));
  return set;
}

MeasurementSet readMeasurementSet(const std::string& path, std::size_t min_rows, const std::string& average_column) {
  std::ifstream in(path);
  if (!in) throw ParameterError("cannot read measurement file '" + path + "'");
  std::stringstream text;
  text << in.rdbuf();
  return parseMeasurementSet(text.str(), path, min_rows, average_column);
}

MeasurementSet readMeasurementSets(const std::vector<std::string>& paths, std::size_t min_rows,
                                   const std::string& average_column) {
  if (paths.size() == 1) return readMeasurementSet(paths.front(), min_rows, average_column);
  MeasurementSet all;
  for (const std::string& path : paths) {
    MeasurementSet one = readMeasurementSet(path, 1, average_column);
    all.rows.insert(all.rows.end(), one.rows.begin(), one.rows.end());
    for (const std::string& note : one.notes) all.notes.push_back(path + ": " + note);
  }
  if (all.rows.size() < min_rows) {
    throw ParameterError("only " + std::to_string(all.rows.size()) + " data rows in all; at least " +
                         std::to_string(min_rows) + " are needed");
  }
  return all;
}

MeasurementSet measurementSetFromColumns(const std::vector<std::string>& names,
                                         const std::vector<std::vector<double>>& columns, const std::string& origin,
                                         std::size_t min_rows, const std::string& average_column) {
  if (names.size() != columns.size()) throw ParameterError(origin + ": " + std::to_string(names.size()) +
                                                           " column names for " + std::to_string(columns.size()) +
                                                           " columns");
  const CsvColumns c = readHeader(names, average_column, origin + ": ");
  const std::size_t rows = columns.empty() ? 0 : columns.front().size();
  for (std::size_t k = 0; k < columns.size(); ++k) {
    if (columns[k].size() != rows) {
      throw ParameterError(origin + ": column " + names[k] + " has " + std::to_string(columns[k].size()) +
                           " values, column " + names[0] + " " + std::to_string(rows));
    }
  }
  MeasurementSet set = withNotes(c);
  for (std::size_t i = 0; i < rows; ++i) {
    // Rows are named as a file's lines are, from 1 (a table has no header line).
    const int row = static_cast<int>(i) + 1;
    const std::string at = origin + ": row " + std::to_string(row) + ": ";
    set.rows.push_back(measurementFrom(
        [&](int column) {
          const double v = columns[static_cast<std::size_t>(column)][i];
          if (!std::isfinite(v)) {
            throw ParameterError(at + formatMessage(v) + " in column " + names[static_cast<std::size_t>(column)] +
                                 " is not a finite number");
          }
          return v;
        },
        c, row, at));
    set.rows.back().in_table = true;
  }
  requireRows(set, min_rows, origin + ": ");
  return set;
}

std::vector<Measurement> parseMeasurementsCsv(const std::string& text, const std::string& origin,
                                              std::size_t min_rows, const std::string& average_column) {
  return parseMeasurementSet(text, origin, min_rows, average_column).rows;
}

std::vector<Measurement> readMeasurementsCsv(const std::string& path, std::size_t min_rows,
                                             const std::string& average_column) {
  return readMeasurementSet(path, min_rows, average_column).rows;
}


namespace {


// An angle beyond what the finger can turn: refused, with the degrees hint (a value in degrees read as radians is
// 57 times too large, so a bend of a few degrees already passes a full turn).
void checkAngle(double value_rad, double bound_rad, const char* bound_name, const std::string& column,
                const std::string& where) {
  if (std::fabs(value_rad) <= bound_rad) return;
  throw ParameterError(where + ": " + column + " = " + formatMessage(value_rad) +
                       " rad is beyond " + bound_name + ", more than this finger can bend; were the angles in "
                       "degrees? (radians = degrees x pi/180)");
}

}  // namespace

// How far past the straight finger's length a measured tip may lie: a camera's noise and its marker's size.
constexpr double kCameraReachShare = 0.05;

void checkMeasurementsPlausible(const FingerParameters& parameters, const std::vector<Measurement>& data) {
  const FingerState rest = restState(parameters);
  const double length_m = rest.tip().norm();  // the straight finger's reach: no bent tip reaches farther
  for (const Measurement& m : data) {
    for (std::size_t k = 0; k < m.joint_rad.size(); ++k) {
      checkAngle(m.joint_rad[k], kPi, "pi (half a turn)", "joint_" + std::to_string(k + 1) + "_rad", m.where());
    }
    if (m.hasTipAngle()) checkAngle(m.tip_angle_rad, 2 * kPi, "2 pi (a full turn)", "tip_angle_rad", m.where());
    // The chord turns about half as far as the tip: a full turn of the tip brings it back to its base.
    if (m.hasChordAngle()) checkAngle(m.chord_angle_rad, kPi, "pi (half a turn)", "chord_angle_rad", m.where());
    if (!std::isnan(m.given_average_rad)) checkAngle(m.given_average_rad, kPi, "pi (half a turn)", "the average", m.where());
    if (m.hasTipPosition()) {
      const double reach_m = std::hypot(m.tip_x_m, m.tip_y_m);
      // A camera reads a tip at the straight finger's end a little past it (its noise, the marker's size): a few
      // percent is measurement, more is a wrong origin or scale, and a thousand times is mm in a metre column.
      if (reach_m > length_m * (1 + kCameraReachShare)) {
        const bool mm = reach_m > 100 * length_m;
        throw ParameterError(m.where() + ": the tip (tip_x_m, tip_y_m) = (" +
                             formatMessage(m.tip_x_m) + ", " + formatMessage(m.tip_y_m) + ") m lies " +
                             formatMessage(reach_m) + " m from the mount, farther than the finger is long (" +
                             formatMessage(length_m) + " m) by more than a camera's " +
                             formatMessage(100 * kCameraReachShare) + " %" +
                             (mm ? "; were the positions in mm? (m = mm / 1000)"
                                 : "; is the origin at the mount, with x along the straight finger?"));
      }
    }
  }
}

}  // namespace pneumatic_finger
