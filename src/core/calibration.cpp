#include "pneumatic_finger/core/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
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

std::vector<Measurement> parseMeasurementsCsv(const std::string& text, const std::string& origin,
                                              std::size_t min_rows, const std::string& average_column) {
  std::stringstream in(text);
  std::string line;
  int number = 0;
  std::vector<std::string> header;
  int gauge_column = -1;
  int average_index = -1;
  std::vector<int> joint_columns;
  std::vector<Measurement> rows;
  while (std::getline(in, line)) {
    ++number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::vector<std::string> fields = splitCsv(line);
    if (header.empty()) {
      header = fields;
      for (std::size_t i = 0; i < header.size(); ++i) {
        if (header[i] == "gauge_pa") gauge_column = static_cast<int>(i);
        if (!average_column.empty() && header[i] == average_column) average_index = static_cast<int>(i);
      }
      if (!average_column.empty() && average_index < 0) {
        throw ParameterError(where(origin, number) + "header has no '" + average_column + "' column");
      }
      if (gauge_column < 0) throw ParameterError(where(origin, number) + "header has no 'gauge_pa' column");
      for (int k = 1;; ++k) {
        const auto it = std::find(header.begin(), header.end(), "joint_" + std::to_string(k) + "_rad");
        if (it == header.end()) break;
        joint_columns.push_back(static_cast<int>(it - header.begin()));
      }
      if (joint_columns.size() < 2) {
        throw ParameterError(where(origin, number) +
                             "header needs columns joint_1_rad, joint_2_rad, ... (at least two joints)");
      }
      continue;
    }
    if (fields.size() != header.size()) {
      throw ParameterError(where(origin, number) + "has " + std::to_string(fields.size()) + " fields, the header " +
                           std::to_string(header.size()));
    }
    auto number_at = [&](int column) {
      const std::string& f = fields[static_cast<std::size_t>(column)];
      char* end = nullptr;
      const double v = std::strtod(f.c_str(), &end);
      if (f.empty() || *end != '\0' || !std::isfinite(v)) {
        throw ParameterError(where(origin, number) + "'" + f + "' in column " +
                             header[static_cast<std::size_t>(column)] + " is not a finite number");
      }
      return v;
    };
    Measurement m;
    m.line = number;
    m.gauge_pa = number_at(gauge_column);
    if (m.gauge_pa < 0) throw ParameterError(where(origin, number) + "gauge_pa is negative");
    for (int c : joint_columns) m.joint_rad.push_back(number_at(c));
    if (average_index >= 0) m.given_average_rad = number_at(average_index);
    rows.push_back(m);
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

CalibrationObjective parseObjective(const std::string& name) {
  if (name == "minimax") return CalibrationObjective::kMinimax;
  if (name == "least_squares") return CalibrationObjective::kLeastSquares;
  throw ParameterError("unknown objective '" + name + "'; known: minimax, least_squares");
}

const char* objectiveName(CalibrationObjective objective) {
  return objective == CalibrationObjective::kMinimax ? "minimax" : "least_squares";
}

namespace {

struct SearchAxis {
  std::string key;
  bool logarithmic;
  double lo, hi;  // in search coordinates (log10 for logarithmic)
  double toValue(double x) const { return logarithmic ? std::pow(10.0, x) : x; }
};

const char* const kFittable[] = {"shear_modulus_pa", "chamber_gap_m", "wall_critical_height_m", "chamber_height_m"};

SearchAxis axisFor(const std::string& key, const FingerParameters& base) {
  if (key == "shear_modulus_pa") return {key, true, 5.0, 12.0};
  const double l = *std::max_element(base.chamber_height_m.begin(), base.chamber_height_m.end());
  if (key == "chamber_gap_m") return {key, false, 0.0, l};
  return {key, false, 1e-3 * l, (key == "chamber_height_m" ? 4.0 : 1.0) * l};
}

void setKey(FingerParameters& p, const std::string& key, double value) {
  std::vector<double>* target = key == "shear_modulus_pa"       ? &p.shear_modulus_pa
                                : key == "chamber_gap_m"          ? &p.chamber_gap_m
                                : key == "wall_critical_height_m" ? &p.wall_critical_height_m
                                                                  : &p.chamber_height_m;
  std::fill(target->begin(), target->end(), value);
}

// Scan, then golden-section on the bracket around the best scan point.
template <typename F>
double minimize1d(F&& f, double lo, double hi, double& best_value) {
  constexpr int kScan = 41;
  double best_x = lo;
  best_value = std::numeric_limits<double>::infinity();
  int best_i = 0;
  for (int i = 0; i < kScan; ++i) {
    const double x = lo + (hi - lo) * i / (kScan - 1);
    const double v = f(x);
    if (v < best_value) {
      best_value = v;
      best_x = x;
      best_i = i;
    }
  }
  double a = lo + (hi - lo) * std::max(best_i - 1, 0) / (kScan - 1);
  double b = lo + (hi - lo) * std::min(best_i + 1, kScan - 1) / (kScan - 1);
  const double r = (std::sqrt(5.0) - 1) / 2;
  double x1 = b - r * (b - a), x2 = a + r * (b - a);
  double f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < 80 && b - a > 1e-13 * (std::fabs(a) + std::fabs(b) + 1e-300); ++i) {
    if (f1 <= f2) {
      b = x2; x2 = x1; f2 = f1; x1 = b - r * (b - a); f1 = f(x1);
    } else {
      a = x1; x1 = x2; f1 = f2; x2 = a + r * (b - a); f2 = f(x2);
    }
  }
  for (auto [x, v] : {std::pair{x1, f1}, std::pair{x2, f2}}) {
    if (v < best_value) {
      best_value = v;
      best_x = x;
    }
  }
  return best_x;
}

}  // namespace

bool isFittableKey(const std::string& key) {
  return std::find(std::begin(kFittable), std::end(kFittable), key) != std::end(kFittable);
}

std::vector<Residual> residuals(const FingerParameters& parameters, const std::vector<Measurement>& data) {
  FingerModel model(parameters);
  std::vector<Residual> out;
  const int n = parameters.chamber_count;
  for (const Measurement& m : data) {
    const FingerState& s = model.evaluate(m.gauge_pa);
    const double avg = s.joint_angle_rad.tail(n - 1).mean();
    out.push_back({m.gauge_pa, m.averageOuterJoints(), avg, m.joint_rad[0], s.joint_angle_rad[0]});
  }
  return out;
}

CalibrationResult calibrate(const FingerParameters& base, const std::vector<std::string>& keys,
                            const std::vector<Measurement>& data, CalibrationObjective objective) {
  if (keys.empty() || keys.size() > 2) throw ParameterError("calibration fits one or two parameters");
  for (const auto& k : keys) {
    if (!isFittableKey(k)) {
      throw ParameterError("parameter '" + k +
                           "' cannot be fitted; fittable: shear_modulus_pa, chamber_gap_m, wall_critical_height_m, "
                           "chamber_height_m");
    }
  }
  if (keys.size() == 2 && keys[0] == keys[1]) throw ParameterError("parameter '" + keys[0] + "' given twice");
  if (base.chamber_count < 2) throw ParameterError("calibration compares joints 2..N: chamber_count must be >= 2");
  for (const auto& m : data) {
    if (m.joint_rad.size() != static_cast<std::size_t>(base.chamber_count)) {
      throw ParameterError("line " + std::to_string(m.line) + ": " + std::to_string(m.joint_rad.size()) +
                           " measured joints, but chamber_count is " + std::to_string(base.chamber_count));
    }
  }
  // mu goes innermost: every residual is monotone in mu, so for fixed other keys the largest |error| is
  // quasi-convex in log mu and the inner search is exact.
  std::vector<SearchAxis> axes;
  for (const auto& k : keys) axes.push_back(axisFor(k, base));
  std::stable_sort(axes.begin(), axes.end(), [](const SearchAxis& a, const SearchAxis& b) {
    return (a.key != "shear_modulus_pa") && (b.key == "shear_modulus_pa");
  });

  CalibrationResult result;
  FingerParameters trial = base;
  auto objectiveAt = [&](const std::vector<double>& x) {
    for (std::size_t i = 0; i < axes.size(); ++i) setKey(trial, axes[i].key, axes[i].toValue(x[i]));
    for (int i = 0; i < trial.chamber_count; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (trial.wall_critical_height_m[k] > trial.chamber_height_m[k]) return std::numeric_limits<double>::infinity();
    }
    double value = 0.0;
    for (const Residual& r : residuals(trial, data)) {
      ++result.model_evaluations;
      const double e = r.error_rad();
      value = objective == CalibrationObjective::kMinimax ? std::max(value, std::fabs(e)) : value + e * e;
    }
    return value;
  };
  std::vector<double> x(axes.size());
  double best = 0.0;
  if (axes.size() == 1) {
    x[0] = minimize1d([&](double v) { x[0] = v; return objectiveAt(x); }, axes[0].lo, axes[0].hi, best);
  } else {
    auto inner = [&](double outer, double& value) {
      std::vector<double> y = {outer, 0.0};
      return minimize1d([&](double v) { y[1] = v; return objectiveAt(y); }, axes[1].lo, axes[1].hi, value);
    };
    x[0] = minimize1d([&](double v) { double value; inner(v, value); return value; }, axes[0].lo, axes[0].hi, best);
    x[1] = inner(x[0], best);
  }
  for (std::size_t i = 0; i < axes.size(); ++i) setKey(trial, axes[i].key, axes[i].toValue(x[i]));
  // Report in the caller's key order.
  result.parameters = trial;
  result.keys = keys;
  for (const auto& k : keys) {
    for (std::size_t i = 0; i < axes.size(); ++i) {
      if (axes[i].key == k) result.values.push_back(axes[i].toValue(x[i]));
    }
  }
  result.objective_value = best;
  result.residuals = residuals(trial, data);
  return result;
}

}  // namespace pneumatic_finger
