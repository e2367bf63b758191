// finger_urdf: the finger's URDF (generated with urdfdom) to stdout or a file. See the README, "Tools".
#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>

#include "pneumatic_finger/core/drawing.hpp"
#include "pneumatic_finger/core/pressure_range.hpp"
#include "pneumatic_finger/description/body_mesh.hpp"
#include "pneumatic_finger/description/finger_urdf.hpp"
#include "pneumatic_finger/sim/finger_mjcf.hpp"
#include "pneumatic_finger/tools/tool_support.hpp"

namespace pf = pneumatic_finger;

namespace {

// "X,Y,Z", or a launch file's "[x, y, z]".
std::array<double, 3> parseTriple(const std::string& option, const std::string& given) {
  std::string text;
  for (char c : given) {
    if (c != '[' && c != ']' && c != ' ') text += c;
  }
  const std::vector<std::string> f = pf::splitFields(text);
  if (f.size() != 3) throw pf::ParameterError(option + " expects three numbers X,Y,Z, got '" + text + "'");
  return {pf::parseFiniteOption(option, f[0]), pf::parseFiniteOption(option, f[1]), pf::parseFiniteOption(option, f[2])};
}

// --gauge-pa through the range rule of every interface (pressure_range.hpp), in its words: above --max-gauge-pa the
// springs of the finger there; a vacuum, the straight finger's (the model has none).
double springGaugePa(const std::string& text, const pf::PressureRange& range, double atmospheric_pa) {
  const double requested = pf::parseFiniteOption("--gauge-pa", text);
  try {
    pf::refuseNegativeAbsolute(requested, atmospheric_pa);
  } catch (const pf::ParameterError& e) {
    throw pf::ParameterError(std::string("--gauge-pa: ") + e.what());
  }
  const pf::RangeCheck check = pf::checkGaugeRange(requested, range);
  if (check.clamped) {
    std::cerr << "finger_urdf: warning: " << pf::clampedMessage(requested, range) << " (the springs are written there)\n";
  } else if (requested < 0.0) {
    std::cerr << "finger_urdf: warning: " << pf::vacuumMessage(requested) << "'s springs are written (at rest)\n";
    return 0.0;
  } else if (check.above_validated) {
    std::cerr << "finger_urdf: warning: " << pf::aboveValidatedMessage(requested, range) << "\n";
  }
  return check.gauge_pa;
}

// One finger of the gripper file (the one with --prefix), as its finger_node describes it.
// Its joint limits at the top of its parameter file's range, or at --max-gauge-pa's when given.
std::string gripperFingerUrdf(const std::string& gripper, const pf::FingerUrdfOptions& options, bool max_given) {
  for (const pf::GripperFinger& f : pf::loadGripperFile(gripper)) {
    if (f.mount.prefix != options.prefix) continue;
    pf::FingerUrdfOptions mount = f.mount;
    if (max_given) mount.max_gauge_pa = options.max_gauge_pa;
    return pf::fingerUrdf(f.parameters, mount);
  }
  throw pf::ParameterError("gripper file '" + gripper + "' has no finger with prefix '" + options.prefix + "'");
}

// What else finger_urdf writes instead of one finger's URDF: the cell composed, a MuJoCo model, the body's mesh.
struct OutputKinds {
  std::string robot, gripper;
  bool mjcf = false, stl = false;
  pf::MjcfOptions mjcf_options;
  std::string mjcf_gauge;

  void addTo(CLI::App& app) {
    auto* robot_opt = app.add_option("--robot", robot, "compose: the robot's URDF, to which every finger of --gripper "
                                                        "is attached");
    auto* gripper_opt = app.add_option("--gripper", gripper,
                                       "the gripper file (YAML: per finger prefix, parent, xyz, rpy, config); with "
                                       "--robot compose them all, without it write the finger with --prefix");
    robot_opt->needs(gripper_opt);
    app.add_flag("--mjcf", mjcf,
                 "write a MuJoCo model (MJCF) instead: the finger's joints carry springs that hold the twin's shape "
                 "and moments at --gauge-pa (docs/SIMULATION.md)");
    app.add_option("--gauge-pa", mjcf_gauge, "with --mjcf: the pressure whose springs the joints carry (Pa gauge; 0)");
    app.add_flag("--stl", stl,
                 "write the drawn body as a mesh instead: ASCII STL in metres, the elastomer with its cavities "
                 "(docs/DRAWING.md, \"The body as a mesh\"); needs a drawing");
  }
};

// The text finger_urdf writes for @p kinds: the MJCF, the composed cell, one gripper finger, the body's mesh or the
// finger's URDF.
std::string describe(pf::ParameterOptions& parameters, pf::FingerUrdfOptions& options, const OutputKinds& kinds,
                     const std::string& max_text) {
  // The file's range by the loader's one rule, its top replaced by --max-gauge-pa when given.
  const pf::PressureRange range = parameters.loadRange(max_text);
  options.max_gauge_pa = range.max_gauge_pa;
  if (!kinds.mjcf_gauge.empty() && !kinds.mjcf) throw pf::ParameterError("--gauge-pa needs --mjcf");
  if (kinds.stl) {
    if (kinds.mjcf || !kinds.gripper.empty()) throw pf::ParameterError("--stl writes one drawn body: no --mjcf, --gripper");
    const std::optional<pf::ActuatorDrawing> drawing = pf::drawingFromRaw(parameters.load().drawing);
    if (!drawing) throw pf::ParameterError("--stl: the parameters have no drawing (docs/DRAWING.md)");
    return pf::meshToStl(pf::drawnBodyMesh(*drawing), options.prefix + "body");
  }
  if (kinds.mjcf) {
    pf::MjcfOptions mjcf_options = kinds.mjcf_options;
    if (!kinds.mjcf_gauge.empty()) {
      mjcf_options.gauge_pa = springGaugePa(kinds.mjcf_gauge, range, parameters.load().atmospheric_pressure_pa);
    }
    if (!kinds.gripper.empty() && kinds.robot.empty()) {
      throw pf::ParameterError("--mjcf with --gripper needs --robot (the whole cell), or neither (one finger)");
    }
    return kinds.robot.empty() ? pf::fingerMjcf(parameters.load(), options, mjcf_options)
                               : pf::composedMjcf(kinds.robot, kinds.gripper, mjcf_options);
  }
  // One description for the whole robot: what robot_state_publisher, rviz and a planner read.
  if (!kinds.robot.empty()) return pf::composeRobotUrdfFiles(kinds.robot, kinds.gripper);
  if (!kinds.gripper.empty()) return gripperFingerUrdf(kinds.gripper, options, !max_text.empty());
  return pf::fingerUrdf(parameters.load(), options);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("The finger's URDF chain, generated with urdfdom, to stdout or a file.", "finger_urdf");
  pf::ParameterOptions parameters;
  parameters.addTo(app);
  pf::FingerUrdfOptions options;
  std::string xyz, rpy, output, max_text;
  app.add_option("--prefix", options.prefix, "prefix of every link and joint name")->capture_default_str();
  app.add_option("--parent", options.parent_frame, "the link the finger is mounted on")->capture_default_str();
  app.add_option("--xyz", xyz, "mount position X,Y,Z in the parent (m)");
  app.add_option("--rpy", rpy, "mount orientation R,P,Y in the parent (rad)");
  app.add_option("--max-gauge-pa", max_text,
                 "pressure that sets the joint limits (Pa gauge); default: the parameter file's max_gauge_pa");
  app.add_option("-o,--output", output, "write here instead of stdout");
  OutputKinds kinds;
  kinds.addTo(app);
  return pf::runTool("finger_urdf", app, argc, argv, [&] {
    if (!xyz.empty()) options.mount_xyz_m = parseTriple("--xyz", xyz);
    if (!rpy.empty()) options.mount_rpy_rad = parseTriple("--rpy", rpy);
    const std::string text = describe(parameters, options, kinds, max_text);
    if (output.empty()) {
      std::cout << text;
    } else {
      std::ofstream out(output);
      if (!(out << text)) throw pf::ParameterError("cannot write '" + output + "'");
    }
    return 0;
  });
}
