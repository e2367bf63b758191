// finger_calibrate: fit the model's effective parameters to measured joint angles. See the README, "Tools".
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "pneumatic_finger/core/calibration.hpp"
#include "pneumatic_finger/tools/tool_support.hpp"
#include "pneumatic_finger/core/units.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pf = pneumatic_finger;

namespace {

constexpr const char* kDescription =
    "Fits the model's effective parameters (default shear_modulus_pa,chamber_gap_m) to the measured average of\n"
    "joints 2..N, prints the paper's Table 2 layout in degrees with joint 1 and leave-one-out errors, and writes the\n"
    "calibrated parameter file when --output is given.";

constexpr double kDeg = pf::kDegPerRad;

std::string fmt(const char* format, double v) {
  char b[64];
  std::snprintf(b, sizeof b, format, v);
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app(kDescription, "finger_calibrate");
  pf::ParameterOptions parameters;
  parameters.addTo(app);
  std::string data_path, output, objective_name = "minimax", average_column, fit_keys = "shear_modulus_pa,chamber_gap_m";
  app.add_option("--data", data_path, "measured CSV (gauge_pa, joint_n_rad); default: the package's data/sierra2022_table1.csv");
  app.add_option("--fit", fit_keys, "one or two parameter keys to fit, comma-separated")->capture_default_str();
  app.add_option("--objective", objective_name, "minimax or least_squares")->capture_default_str();
  app.add_option("--output", output, "write the calibrated parameter file (YAML) here");
  app.add_option("--average-column", average_column,
                 "take the joints 2..N average from this column (e.g. paper_avg_rad) instead of the joints");
  return pf::runTool("finger_calibrate", app, argc, argv, [&] {
    const std::vector<std::string> keys = pf::splitFields(fit_keys);
    const bool default_data = data_path.empty();
    if (default_data) data_path = pf::packageShareDirectory() + "/data/sierra2022_table1.csv";
    const pf::CalibrationObjective objective = pf::parseObjective(objective_name);
    const pf::FingerParameters base = parameters.load();
    // A fit of k parameters needs more than k rows; leave-one-out needs one more.
    const std::vector<pf::Measurement> data = pf::readMeasurementsCsv(data_path, keys.size() + 2, average_column);
    const pf::CalibrationResult fit = pf::calibrate(base, keys, data, objective);

    std::ostringstream table;
    table << "# data: " << (default_data ? "the package's data/sierra2022_table1.csv" : data_path) << " (" << data.size() << " rows)\n"
          << "# objective: " << objective_name << " over the average of joints 2.." << base.chamber_count
          << (average_column.empty() ? " (mean of the measured joints)" : " (column " + average_column + ")")
          << "; error = model - measured\n# fitted:";
    for (std::size_t i = 0; i < fit.keys.size(); ++i) table << " " << fit.keys[i] << " = " << pf::formatExact(fit.values[i]);
    table << "\n#\n# pressure_kgcm2  measured_avg_deg  model_avg_deg  error_deg  joint1_measured_deg  "
             "joint1_model_deg  joint1_error_deg  leave_one_out_error_deg\n";
    double worst = 0, worst_loo = 0, sum_sq = 0;
    for (std::size_t i = 0; i < data.size(); ++i) {
      std::vector<pf::Measurement> others = data;
      others.erase(others.begin() + static_cast<long>(i));
      const pf::CalibrationResult loo = pf::calibrate(base, keys, others, objective);
      const double loo_error = pf::residuals(loo.parameters, {data[i]})[0].error_rad();
      const pf::Residual& r = fit.residuals[i];
      worst = std::max(worst, std::fabs(r.error_rad()));
      worst_loo = std::max(worst_loo, std::fabs(loo_error));
      sum_sq += r.error_rad() * r.error_rad();
      table << "# " << fmt("%14.3f", r.gauge_pa / pf::kPaPerKgfPerCm2) << fmt("%18.3f", r.measured_avg_rad * kDeg)
            << fmt("%15.3f", r.model_avg_rad * kDeg) << fmt("%11.3f", r.error_rad() * kDeg)
            << fmt("%21.3f", r.measured_joint1_rad * kDeg) << fmt("%18.3f", r.model_joint1_rad * kDeg)
            << fmt("%18.3f", r.joint1_error_rad() * kDeg) << fmt("%25.3f", loo_error * kDeg) << "\n";
    }
    table << "#\n# largest |error| " << fmt("%.3f", worst * kDeg) << " deg (the paper: 0.647 deg), rms "
          << fmt("%.3f", std::sqrt(sum_sq / static_cast<double>(data.size())) * kDeg)
          << " deg; largest leave-one-out |error| " << fmt("%.3f", worst_loo * kDeg) << " deg\n";
    std::cout << table.str();
    if (!output.empty()) {
      std::ofstream out(output);
      if (!out) throw pf::ParameterError("cannot write '" + output + "'");
      out << "# The calibrated actuator: written by `finger_calibrate --output` (see docs/ACCURACY.md).\n"
          << "# Every key's default in the code (parameters.cpp) equals this file; a test checks it.\n"
          << table.str() << "\n"
          << pf::parametersToYaml(fit.parameters);
    }
    return 0;
  });
}
