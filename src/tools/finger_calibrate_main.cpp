// finger_calibrate: fit the model's effective parameters to measured joint angles. See the README, "Tools".
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "pneumatic_finger/calibration.hpp"
#include "pneumatic_finger/tool_support.hpp"
#include "pneumatic_finger/yaml_parameters.hpp"

namespace pf = pneumatic_finger;

namespace {

const char* const kUsage =
    "usage: finger_calibrate [--config FILE.yaml] [--set KEY=VALUE]... [--data MEASURED.csv]\n"
    "                        [--fit KEY[,KEY]] [--objective minimax|least_squares] [--output FILE.yaml]\n"
    "                        [--average-column COLUMN]\n"
    "Fits KEY (default shear_modulus_pa,chamber_gap_m) to the measured average of joints 2..N, prints the\n"
    "paper's Table 2 layout in degrees with joint 1 and leave-one-out errors, and writes the calibrated\n"
    "parameter file when --output is given. Default data: the package's data/sierra2022_table1.csv.\n"
    "--average-column takes the joints 2..N average from COLUMN (e.g. paper_avg_rad) instead of the joints.\n";

constexpr double kDeg = 180.0 / 3.14159265358979323846;

std::string defaultDataFile(const char* argv0) {
  const std::string config = pf::defaultParameterFile(argv0);
  return config.substr(0, config.rfind("/config/")) + "/data/sierra2022_table1.csv";
}

std::string fmt(const char* format, double v) {
  char b[64];
  std::snprintf(b, sizeof b, format, v);
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::string config, data_path, output, objective_name = "minimax", average_column;
    std::vector<std::string> sets, keys = {"shear_modulus_pa", "chamber_gap_m"};
    for (int i = 1; i < argc; ++i) {
      const std::string opt = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw pf::ParameterError(opt + " needs a value");
        return argv[++i];
      };
      if (opt == "--config") config = value();
      else if (opt == "--set") sets.push_back(value());
      else if (opt == "--data") data_path = value();
      else if (opt == "--output") output = value();
      else if (opt == "--objective") objective_name = value();
      else if (opt == "--average-column") average_column = value();
      else if (opt == "--fit") {
        keys.clear();
        std::stringstream s(value());
        std::string k;
        while (std::getline(s, k, ',')) keys.push_back(k);
      } else if (opt == "--help" || opt == "-h") {
        std::cout << kUsage;
        return 0;
      } else {
        throw pf::ParameterError("unknown option '" + opt + "'");
      }
    }
    const bool default_data = data_path.empty();
    if (default_data) data_path = defaultDataFile(argv[0]);
    const pf::CalibrationObjective objective = pf::parseObjective(objective_name);
    const pf::FingerParameters base = pf::loadToolParameters(config, sets, argv[0]);
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
      table << "# " << fmt("%14.3f", r.gauge_pa / 98066.5) << fmt("%18.3f", r.measured_avg_rad * kDeg)
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
  } catch (const pf::ParameterError& e) {
    std::cerr << "finger_calibrate: error: " << e.what() << "\n";
    return 2;
  }
}
