// finger_urdf: the finger's URDF (generated with urdfdom) to stdout or a file. See the README, "Tools".
#include <fstream>
#include <iostream>
#include <sstream>

#include "pneumatic_finger/finger_urdf.hpp"
#include "pneumatic_finger/tool_support.hpp"

namespace pf = pneumatic_finger;

int main(int argc, char** argv) {
  try {
    std::string config, output;
    std::vector<std::string> sets;
    pf::FingerUrdfOptions options;
    auto triple = [](const std::string& opt, const std::string& text) {
      std::array<double, 3> v{};
      std::stringstream s(text);
      std::string item;
      for (std::size_t i = 0; i < 3; ++i) {
        if (!std::getline(s, item, ',')) throw pf::ParameterError(opt + " expects X,Y,Z, got '" + text + "'");
        v[i] = pf::parseFiniteOption(opt, item);
      }
      if (std::getline(s, item, ',')) throw pf::ParameterError(opt + " expects three numbers, got '" + text + "'");
      return v;
    };
    for (int i = 1; i < argc; ++i) {
      const std::string opt = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw pf::ParameterError(opt + " needs a value");
        return argv[++i];
      };
      if (opt == "--config") config = value();
      else if (opt == "--set") sets.push_back(value());
      else if (opt == "--prefix") options.prefix = value();
      else if (opt == "--parent") options.parent_frame = value();
      else if (opt == "--xyz") options.mount_xyz_m = triple(opt, value());
      else if (opt == "--rpy") options.mount_rpy_rad = triple(opt, value());
      else if (opt == "--max-gauge-pa") options.max_gauge_pa = pf::parseFiniteOption(opt, value());
      else if (opt == "--output" || opt == "-o") output = value();
      else if (opt == "--help" || opt == "-h") {
        std::cout << "usage: finger_urdf [--config FILE.yaml] [--set KEY=VALUE]... [--prefix P] [--parent FRAME]\n"
                     "                   [--xyz X,Y,Z] [--rpy R,P,Y] [--max-gauge-pa P] [--output FILE.urdf]\n";
        return 0;
      } else {
        throw pf::ParameterError("unknown option '" + opt + "'");
      }
    }
    if (!(options.max_gauge_pa > 0)) throw pf::ParameterError("--max-gauge-pa must be > 0");
    const std::string urdf = pf::fingerUrdf(pf::loadToolParameters(config, sets, argv[0]), options);
    if (output.empty()) {
      std::cout << urdf;
    } else {
      std::ofstream out(output);
      if (!(out << urdf)) throw pf::ParameterError("cannot write '" + output + "'");
    }
    return 0;
  } catch (const pf::ParameterError& e) {
    std::cerr << "finger_urdf: error: " << e.what() << "\n";
    return 2;
  }
}
