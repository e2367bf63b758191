// A coupon test read from a CSV or from columns, and checked (coupon.hpp): every refusal names the row and what was
// expected, the same words in finger_calibrate and Python.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "pneumatic_finger/calibration/coupon.hpp"
#include "pneumatic_finger/core/csv_fields.hpp"
#include "pneumatic_finger/core/parameters.hpp"

namespace pneumatic_finger {

namespace {

constexpr double kMostStrain = 20.0;        // 2000 %: past any elastomer's rupture; a larger one is percent
constexpr double kLeastSecantModulusPa = 1e3;  // softer than any elastomer a finger is cast in: kPa or MPa given
constexpr double kFallShare = 0.02;         // a stress falling by more than this share of its largest so far
constexpr std::size_t kLeastRows = 4;       // three keys and one more row

// A row as a person finds it: its file's line (an editor's count, comments and header included), else its index.
std::string rowName(const std::string& origin, std::size_t i, int line = 0) {
  return line > 0 ? origin + ":" + std::to_string(line) + " (data row " + std::to_string(i + 1) + ")"
                  : origin + ": row " + std::to_string(i + 1);
}

// The columns of the header, or throws naming what it lacks.
void headerColumns(const std::vector<std::string>& header, const std::string& at, int& strain, int& stress) {
  strain = stress = -1;
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == "engineering_strain") strain = static_cast<int>(i);
    if (header[i] == "nominal_stress_pa") stress = static_cast<int>(i);
  }
  if (strain >= 0 && stress >= 0) return;
  std::string hint;
  for (const std::string& name : header) {
    if (name == "nominal_stress_mpa" || name == "nominal_stress_kpa" || name == "stress") hint = "; give the stress in Pa";
    if (name == "strain_percent" || name == "strain") hint += "; give the engineering strain as a ratio (0.5 for 50 %)";
  }
  throw ParameterError(at + "header needs the columns engineering_strain and nominal_stress_pa" + hint);
}

double number(const std::string& text, const std::string& at, const char* column) {
  const std::optional<double> v = readNumber(text);  // inf and nan are read, and checkCouponRows refuses them
  if (!v) throw ParameterError(at + ": " + column + " '" + text + "' is not a number");
  return *v;
}

}  // namespace

void checkCouponRows(const std::vector<CouponRow>& rows, const std::string& origin) {
  if (rows.size() < kLeastRows) {
    throw ParameterError(origin + ": " + std::to_string(rows.size()) + " rows; a coupon fit needs at least " +
                         std::to_string(kLeastRows));
  }
  double largest_pa = 0.0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const CouponRow& r = rows[i];
    const std::string at = rowName(origin, i, r.line);
    if (!std::isfinite(r.engineering_strain) || !std::isfinite(r.nominal_stress_pa)) {
      throw ParameterError(at + ": strain " + formatMessage(r.engineering_strain) + " and stress " +
                           formatMessage(r.nominal_stress_pa) + " Pa must be finite numbers");
    }
    if (r.engineering_strain < 0.0 || (i > 0 && r.engineering_strain <= rows[i - 1].engineering_strain)) {
      throw ParameterError(at + ": engineering strain " + formatMessage(r.engineering_strain) +
                           " must be >= 0 and rise row by row (a tension test's loading curve)");
    }
    if (r.engineering_strain > kMostStrain) {
      throw ParameterError(at + ": engineering strain " + formatMessage(r.engineering_strain) + " is past " +
                           formatMessage(kMostStrain) + " (2000 %); is it in percent? Give a ratio (0.5 for 50 %)");
    }
    if (r.nominal_stress_pa < largest_pa * (1.0 - kFallShare)) {
      throw ParameterError(at + ": the stress falls to " + formatMessage(r.nominal_stress_pa) + " Pa from " +
                           formatMessage(largest_pa) + " Pa: past rupture, or unloading; give the loading curve up "
                           "to the largest stress");
    }
    largest_pa = std::max(largest_pa, r.nominal_stress_pa);
  }
  const CouponRow& last = rows.back();
  const double secant_pa = last.nominal_stress_pa / last.engineering_strain;
  if (!(secant_pa >= kLeastSecantModulusPa)) {
    throw ParameterError(origin + ": a stress of " + formatMessage(last.nominal_stress_pa) + " at a strain of " +
                         formatMessage(last.engineering_strain) + " is a secant modulus of " + formatMessage(secant_pa) +
                         " Pa, softer than any elastomer; is the stress in kPa or MPa (N/mm^2), or the strain in percent? Give the "
                         "stress in Pa and the strain as a ratio (0.5 for 50 %)");
  }
}

CouponTest couponFromColumns(const std::vector<double>& engineering_strain, const std::vector<double>& nominal_stress_pa,
                             const std::string& origin) {
  if (engineering_strain.size() != nominal_stress_pa.size()) {
    throw ParameterError(origin + ": " + std::to_string(engineering_strain.size()) + " strains and " +
                         std::to_string(nominal_stress_pa.size()) + " stresses; give one of each per row");
  }
  CouponTest test;
  test.origin = origin;
  for (std::size_t i = 0; i < engineering_strain.size(); ++i) {
    test.rows.push_back({engineering_strain[i], nominal_stress_pa[i]});
  }
  checkCouponRows(test.rows, origin);
  return test;
}

CouponTest loadCouponCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ParameterError(path + ": cannot open the coupon test");
  CouponTest test;
  test.origin = path;
  int strain = -1, stress = -1, line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
    const std::string at = path + ":" + std::to_string(line_number) + ": ";
    const std::vector<std::string> fields = strain < 0 ? splitCsvHeader(line, at) : splitCsv(line);
    if (strain < 0) {
      headerColumns(fields, at, strain, stress);
      continue;
    }
    const std::string row = rowName(path, test.rows.size(), line_number);
    if (fields.size() <= static_cast<std::size_t>(std::max(strain, stress))) {
      throw ParameterError(row + ": " + std::to_string(fields.size()) + " columns, fewer than the header's");
    }
    test.rows.push_back({number(fields[static_cast<std::size_t>(strain)], row, "engineering_strain"),
                         number(fields[static_cast<std::size_t>(stress)], row, "nominal_stress_pa"), line_number});
  }
  if (strain < 0) throw ParameterError(path + ": no header (engineering_strain,nominal_stress_pa)");
  checkCouponRows(test.rows, path);
  return test;
}

}  // namespace pneumatic_finger
