// finger_model: the model from the command line, as CSV (one row per pressure). See the README, "Tools".
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "pneumatic_finger/finger_model.hpp"
#include "pneumatic_finger/tool_support.hpp"

namespace pf = pneumatic_finger;

namespace {

const char* const kUsage =
    "usage: finger_model [--config FILE.yaml] [--set KEY=VALUE]... [--solver robust|paper|table]\n"
    "                    (--gauge-pa P)... | --sweep-pa FROM:TO:COUNT\n"
    "       finger_model --parameters     (the parameter table, as Markdown)\n"
    "Prints CSV: gauge_pa,stretch,bulge_m,half_angle_rad,joint_1_rad..joint_N_rad,tip_x_m,tip_y_m\n"
    "(stretch, bulge and half angle of chamber 1; 17 significant digits). Exit 2 on bad input.\n";

struct Arguments {
  std::string config;
  std::vector<std::string> sets;
  std::string solver = "robust";
  std::vector<double> pressures;
  bool sweep = false;
  bool parameters_table = false;
};

std::vector<double> parseSweep(const std::string& text) {
  std::stringstream s(text);
  std::string from, to, count;
  if (!std::getline(s, from, ':') || !std::getline(s, to, ':') || !std::getline(s, count) ||
      count.find(':') != std::string::npos) {
    throw pf::ParameterError("--sweep-pa expects FROM:TO:COUNT, got '" + text + "'");
  }
  const double a = pf::parseFiniteOption("--sweep-pa FROM", from);
  const double b = pf::parseFiniteOption("--sweep-pa TO", to);
  const double n = pf::parseFiniteOption("--sweep-pa COUNT", count);
  if (n < 1 || n > 1e7 || n != static_cast<double>(static_cast<long>(n))) {
    throw pf::ParameterError("--sweep-pa COUNT = " + count + " must be a whole number in [1, 10000000]");
  }
  std::vector<double> out;
  const long k = static_cast<long>(n);
  for (long i = 0; i < k; ++i) out.push_back(k == 1 ? a : a + (b - a) * static_cast<double>(i) / (k - 1));
  return out;
}

Arguments parse(int argc, char** argv) {
  Arguments args;
  bool gauge_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string opt = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw pf::ParameterError(opt + " needs a value");
      return argv[++i];
    };
    if (opt == "--config") {
      args.config = value();
    } else if (opt == "--set") {
      args.sets.push_back(value());
    } else if (opt == "--solver") {
      args.solver = value();
    } else if (opt == "--gauge-pa") {
      const std::string v = value();
      // NaN and inf are refused here: a pressure the model cannot place is an input error, not a row.
      args.pressures.push_back(pf::parseFiniteOption("--gauge-pa", v));
      gauge_given = true;
    } else if (opt == "--sweep-pa") {
      if (args.sweep) throw pf::ParameterError("--sweep-pa given twice");
      args.pressures = parseSweep(value());
      args.sweep = true;
    } else if (opt == "--parameters") {
      args.parameters_table = true;
    } else if (opt == "--help" || opt == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else {
      throw pf::ParameterError("unknown option '" + opt + "'");
    }
  }
  if (args.parameters_table) return args;
  if (gauge_given && args.sweep) throw pf::ParameterError("give --gauge-pa or --sweep-pa, not both");
  if (args.pressures.empty()) throw pf::ParameterError("no pressure given: use --gauge-pa P or --sweep-pa FROM:TO:COUNT");
  return args;
}

void printParameterTable() {
  std::cout << "| key | symbol | unit | default | allowed | per chamber | meaning |\n"
            << "|---|---|---|---|---|---|---|\n";
  for (const auto& s : pf::parameterSpecs()) {
    std::cout << "| `" << s.key << "` | " << s.symbol << " | " << s.unit << " | " << pf::formatExact(s.default_value)
              << " | " << pf::describeRange(s) << " | "
              << (s.shape == pf::ParameterShape::kPerChamber ? "scalar or list of N" : "scalar") << " | "
              << s.description << " |\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Arguments args = parse(argc, argv);
    if (args.parameters_table) {
      printParameterTable();
      return 0;
    }
    pf::ModelOptions options;
    options.solver = pf::parseSolverName(args.solver);
    pf::FingerModel model(pf::loadToolParameters(args.config, args.sets, argv[0]), options);
    const int n = model.chamberCount();
    std::ostringstream out;
    out << "gauge_pa,stretch,bulge_m,half_angle_rad";
    for (int j = 1; j <= n; ++j) out << ",joint_" << j << "_rad";
    out << ",tip_x_m,tip_y_m\n";
    bool warned = false;
    for (double p : args.pressures) {
      const pf::FingerState& s = model.evaluate(p);
      if (s.status == pf::EvaluationStatus::kVacuum && !warned) {
        std::cerr << "finger_model: warning: gauge pressure " << pf::formatExact(p)
                  << " Pa is negative (vacuum), outside the model; printing the straight finger\n";
        warned = true;
      }
      out << pf::formatExact(p) << ',' << pf::formatExact(s.stretch[0]) << ',' << pf::formatExact(s.bulge_m[0]) << ','
          << pf::formatExact(s.half_angle_rad[0]);
      for (int j = 0; j < n; ++j) out << ',' << pf::formatExact(s.joint_angle_rad[j]);
      const Eigen::Vector2d tip = s.tip();
      out << ',' << pf::formatExact(tip.x()) << ',' << pf::formatExact(tip.y()) << '\n';
    }
    std::cout << out.str();
    return 0;
  } catch (const pf::ParameterError& e) {
    std::cerr << "finger_model: error: " << e.what() << "\n";
    return 2;
  }
}
