// finger_model's listings (an internal header, beside finger_model_main.cpp): what it prints instead of rows, and
// exits: the parameter tables, or where the model's finger changes.
#pragma once

#include <CLI/CLI.hpp>

#include <cmath>
#include <iostream>
#include <string>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/side_grip.hpp"
#include "pneumatic_finger/tools/tool_support.hpp"

namespace pneumatic_finger_tools {

namespace pf = pneumatic_finger;

// The parameter table (docs/PARAMETERS.md), from its one definition.
inline void printParameterTable() {
  std::cout << "| key | symbol | unit | default | allowed | per chamber | meaning |\n"
            << "|---|---|---|---|---|---|---|\n";
  for (const auto& s : pf::parameterSpecs()) {
    std::cout << "| `" << s.key << "` | " << s.symbol << " | " << s.unit << " | "
              << (s.shape == pf::ParameterShape::kChoice ? pf::formatParameterValue(s, s.default_value)
                                                          : pf::formatExact(s.default_value))
              << " | " << pf::describeRange(s) << " | "
              << (s.shape == pf::ParameterShape::kPerChamber ? "scalar or list of N" : "scalar") << " | "
              << s.description << " |\n";
  }
}

// A drawing key's default: a number, "required", or "from another key" where its meaning says which (NaN default).
inline std::string defaultText(const pf::ParameterSpec& s) {
  if (!std::isnan(s.default_value)) return pf::formatExact(s.default_value);
  return std::string(s.description).find("(default:") == std::string::npos ? "required" : "from another key";
}

// The drawing's keys (docs/DRAWING.md), from their one definition.
inline void printDrawingTable() {
  std::cout << "| key (under `drawing:`) | unit | default | allowed | meaning |\n|---|---|---|---|---|\n";
  for (const auto& s : pf::drawingParameterSpecs()) {
    std::cout << "| `" << s.key << "` | " << s.unit << " | "
              << defaultText(s) << " | "
              << pf::describeRange(s) << " | " << s.description << " |\n";
  }
}

// --pressures: where the model's finger changes, one CSV row under the names Python's FingerModel gives them (and
// finger_node's diagnostics report the snap): the walls' first touch, the snap (the limit point where a wall folds,
// else where it is softest), the limit point (inf where no wall folds) and the far branch's turning point; with a
// part (--grip-part), the lowest pressure up to the range's top at which the gripper holds it (nan: none).
inline void printModelPressures(const pf::FingerModel& model, const std::string& grip_part, double max_gauge_pa) {
  std::string grip;  // asked first: a part that is not one is refused before anything is printed
  if (!grip_part.empty()) {
    pf::SideGripTask part = pf::parseSideGripTask(grip_part);
    part.max_gauge_pa = max_gauge_pa;
    std::string why;
    grip = "," + pf::formatExact(pf::holdingGaugePa(model, part, &why));
    if (!why.empty()) std::cerr << "finger_model: warning: the part is not held: " << why << '\n';
  }
  std::cout << "contact_gauge_pa,snap_gauge_pa,limit_gauge_pa,far_turning_gauge_pa"
            << (grip_part.empty() ? "" : ",grip_gauge_pa") << '\n'
            << pf::formatExact(model.contactGaugePa()) << ',' << pf::formatExact(model.snapGaugePa()) << ','
            << pf::formatExact(model.limitGaugePa()) << ',' << pf::formatExact(model.farTurningGaugePa()) << grip
            << '\n';
}

// What finger_model prints instead of rows, and exits: the parameter tables, or the model's pressures.
struct Listings {
  bool parameters = false, drawing = false, pressures = false;
  std::string grip_part;

  void addTo(CLI::App& app) {
    app.add_flag("--parameters", parameters, "print the parameter table (Markdown) and exit");
    app.add_flag("--drawing-parameters", drawing, "print the drawing's keys (Markdown, docs/DRAWING.md) and exit");
    app.add_flag("--pressures", pressures,
                 "print where the finger changes (Pa gauge, as Python's FingerModel names them): contact_gauge_pa, "
                 "snap_gauge_pa, limit_gauge_pa (inf: no wall folds), far_turning_gauge_pa; and exit");
    app.add_option("--grip-part", grip_part,
                   "with --pressures, add grip_gauge_pa: the lowest pressure at which the gripper holds the part "
                   "mass_kg=M,diameter_m=D[,lift_mps2=A,fingers=3,mount_radius_m=0.035,friction=1,margin=1.5,"
                   "limit_share=0.9] by the cell's grasp rule (docs/DESIGN.md, \"A grip\")");
  }
  // True when one was asked for, and printed. @throws ParameterError for --grip-part without --pressures
  bool print(const pf::ParameterOptions& file, const std::string& max_gauge) const {
    if (!grip_part.empty() && !pressures) throw pf::ParameterError("--grip-part goes with --pressures");
    if (parameters) printParameterTable();
    else if (drawing) printDrawingTable();
    else if (pressures) {
      printModelPressures(pf::FingerModel(file.load()), grip_part, file.loadRange(max_gauge).max_gauge_pa);
    }
    return parameters || drawing || pressures;
  }
};

}  // namespace pneumatic_finger_tools
