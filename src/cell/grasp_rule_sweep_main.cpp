// grasp_rule_sweep: does the cell's grasp rule hold? For each object mass and lift acceleration, the twin's verdict
// (friction x the fingers' normal forces against the weight, with and without the lift's inertia) beside what MuJoCo
// does with the same gripper, part and lift (docs/SIMULATION.md, "Does the grasp rule hold?"). One CSV row per case.
#include <CLI/CLI.hpp>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <numeric>
#include <string>
#include <vector>

#include "pneumatic_finger/cell/cell_schedule.hpp"
#include "pneumatic_finger/cell/grasp_hold.hpp"
#include "pneumatic_finger/cell/side_grasp.hpp"
#include "pneumatic_finger/core/grasp_plan.hpp"
#include "pneumatic_finger/core/smoothstep.hpp"
#include "pneumatic_finger/core/regulator.hpp"
#include "pneumatic_finger/sim/cell_physics.hpp"
#include "pneumatic_finger/sim/finger_mjcf.hpp"
#include "pneumatic_finger/sim/grasp_lift_trial.hpp"
#include "pneumatic_finger/sim/mjcf_text.hpp"

namespace pf = pneumatic_finger;

namespace {

struct Sweep {
  std::string gripper = "config/gripper.yaml", cell = "config/cell.yaml", arm = "urdf/industrial_arm.urdf";
  std::vector<double> masses_g = {5, 7.5, 10, 12.5, 15, 17.5, 20, 25, 30, 50, 100, 200};
  std::vector<double> accelerations;  // empty: the cell's lift from slow to its fastest (cellLift)
  double lift_m = 0.0;                 // 0: the cell's
  double squeeze_margin_pa = pf::kDefaultSqueezeMarginPa;
  std::string scene_out;  // where to write the first case's scene at the grasp pressure, for MuJoCo's viewer
  pf::MjcfOptions mjcf;   // the engine's step and the fingers' armature
};

// The cell's part and its rule's friction and margin (config/cell.yaml).
struct CellPart {
  double radius_m = 0, height_m = 0, friction = 0, margin = 0;
};

CellPart readCellPart(const std::string& path) {
  const YAML::Node y = YAML::LoadFile(path);
  return {y["object_radius_m"].as<double>(), y["object_height_m"].as<double>(), y["friction_coefficient"].as<double>(),
          y["hold_margin"].as<double>()};
}

// The cell's lift (config/cell.yaml's pick -> above_pick): how far tool0 rises, by MuJoCo's kinematics of the
// composed arm, and the path's peak acceleration at the fastest cycle the schedule runs (kMinCycleTimeS).
struct CellLift {
  double height_m = 0.0, fastest_mps2 = 0.0;
};

CellLift cellLift(const std::string& arm_path, const std::string& gripper_path, const std::string& cell_path) {
  const pf::MujocoModelPtr m = pf::loadMjcfText(pf::composedMjcf(arm_path, gripper_path, pf::MjcfOptions()));
  const pf::MujocoDataPtr d(mj_makeData(m.get()));
  const YAML::Node cell = YAML::LoadFile(cell_path);
  const auto names = cell["arm_joint_names"].as<std::vector<std::string>>();
  const int tool = mj_name2id(m.get(), mjOBJ_BODY, "tool0");
  double z[2] = {0, 0};
  for (int w = 0; w < 2; ++w) {
    const auto q = cell[w == 0 ? "pick" : "above_pick"].as<std::vector<double>>();
    for (std::size_t j = 0; j < names.size(); ++j) {
      d->qpos[m->jnt_qposadr[mj_name2id(m.get(), mjOBJ_JOINT, names[j].c_str())]] = q.at(j);
    }
    mj_kinematics(m.get(), d.get());
    z[w] = d->xpos[3 * tool + 2];
  }
  const auto wp = [&](const char* key) { return cell[key].as<std::vector<double>>(); };
  const pf::CellSchedule fastest({wp("home"), wp("above_pick"), wp("pick"), wp("above_place"), wp("place")},
                                 pf::kMinCycleTimeS);
  const double T = fastest.phaseDurationS(pf::CellPhase::kLift), h = z[1] - z[0];
  return {h, pf::smoothstepPeakAcceleration(h, T)};
}

void printRow(double mass_kg, const pf::LiftMotion& lift, double gauge_pa, const pf::SideGraspForces& twin,
              const CellPart& part, const pf::GraspTrialOutcome& sim) {
  const int fingers = static_cast<int>(twin.normal_force_n.size());
  const double weakest = *std::min_element(twin.normal_force_n.begin(), twin.normal_force_n.end());
  const double twin_sum = std::accumulate(twin.normal_force_n.begin(), twin.normal_force_n.end(), 0.0);
  const double sim_sum = std::accumulate(sim.finger_normal_force_n.begin(), sim.finger_normal_force_n.end(), 0.0);
  const pf::HoldVerdict cell = pf::judgeHold(fingers, weakest, mass_kg, part.friction, part.margin);
  const pf::HoldVerdict lifted = pf::judgeHold(fingers, weakest, mass_kg, part.friction, 1.0, lift.peak_acceleration_mps2);
  const double threshold_kg = part.friction * fingers * weakest / (pf::kStandardGravity + lift.peak_acceleration_mps2);
  std::printf("%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%d,%d,%.6g,%s\n", mass_kg, lift.peak_acceleration_mps2,
              lift.durationS(), gauge_pa, twin_sum, sim_sum, threshold_kg, cell.holds, lifted.holds, sim.carried,
              sim.slip_m, sim.problem.empty() ? "" : ("\"" + sim.problem + "\"").c_str());
}

// The grasp closed without gravity (nothing pulls the part): each finger's normal force by the twin
// (contactNormalForcesN) and by MuJoCo, with the held moments' springs and with the linear ones (N, finger 1).
void printClosedForces(const std::vector<pf::GripperFinger>& fingers, const pf::GraspScene& scene, double gauge_pa,
                       const pf::SideGraspForces& twin, const pf::MjcfOptions& mjcf) {
  pf::GraspLiftTrial trial(fingers, scene, mjcf);
  pf::GraspTrialSettings closed;
  closed.hang_s = closed.after_s = 0.0;
  const double held = trial.run(gauge_pa, pf::LiftMotion{0.0, 1.0}, closed).finger_normal_force_n.at(0);
  closed.held_moments = false;
  const double linear = trial.run(gauge_pa, pf::LiftMotion{0.0, 1.0}, closed).finger_normal_force_n.at(0);
  std::fprintf(stderr, "grasp_rule_sweep: closed at %.0f Pa without gravity, one finger's normal force: the twin "
               "%.4g N; MuJoCo %.4g N with the held moments' springs (%+.1f %%), %.4g N with the linear springs "
               "(%+.1f %%)\n", gauge_pa, twin.normal_force_n.at(0), held, 100 * (held / twin.normal_force_n.at(0) - 1),
               linear, 100 * (linear / twin.normal_force_n.at(0) - 1));
}

// The cell's own lift in MuJoCo (CellPhysics): the fingers fill to @p grasp_pa at the regulator's rate while the arm
// holds the pick pose, the arm's actuators follow the schedule from the pick pose to the pose above it in
// @p lift_s, then hold 1 s. What it did to the part.
struct ArmLift {
  double tool_rise_m = 0.0, part_rise_m = 0.0;
  double largest_tilt_deg = 0.0;   // tool z from straight down, during the lift
  int fewest_fingers = 0;          // fingers touching the part, the fewest during the lift
};

ArmLift armLift(const Sweep& s, const std::vector<pf::GripperFinger>& fingers, const pf::GraspScene& scene,
                double grasp_pa, double lift_s) {
  const YAML::Node cell = YAML::LoadFile(s.cell);
  const auto pick = cell["pick"].as<std::vector<double>>(), above = cell["above_pick"].as<std::vector<double>>();
  pf::CellPhysics physics(pf::readRobotUrdfFile(s.arm), fingers, cell["arm_joint_names"].as<std::vector<std::string>>(),
                          pick, scene, s.mjcf);
  const double rate = pf::gripperFillRatePaPerS(pf::kCellRegulatorFlowM3PerS, fingers.front().parameters,
                                                static_cast<int>(fingers.size()));
  const double dt = physics.model().opt.timestep, hold_s = 1.5;
  double gauge = 0.0, part_z0 = 0.0, tool_z0 = 0.0;
  std::string why;
  std::vector<double> target(pick.size());
  ArmLift out;
  out.fewest_fingers = static_cast<int>(fingers.size());
  for (double t = 0.0; t < hold_s + lift_s + 1.0; t += dt) {
    const double u = std::clamp((t - hold_s) / lift_s, 0.0, 1.0);
    for (std::size_t j = 0; j < target.size(); ++j) target[j] = pick[j] + pf::smoothstep(u) * (above[j] - pick[j]);
    physics.setArmTargets(target);
    gauge = pf::regulatorStep(gauge, grasp_pa, rate, dt);
    if (!physics.step(gauge, why)) throw pf::ParameterError(why);
    if (t < hold_s) part_z0 = physics.partPose().translation().z(), tool_z0 = physics.toolPose().translation().z();
    if (t < hold_s || t > hold_s + lift_s) continue;
    const double down = -physics.toolPose().linear()(2, 2);
    out.largest_tilt_deg = std::max(out.largest_tilt_deg, std::acos(std::min(1.0, down)) * 180.0 / M_PI);
    const std::vector<int> touching = physics.fingerContacts();
    out.fewest_fingers = std::min(out.fewest_fingers,
                                  static_cast<int>(std::count_if(touching.begin(), touching.end(),
                                                                 [](int n) { return n > 0; })));
  }
  out.tool_rise_m = physics.toolPose().translation().z() - tool_z0;
  out.part_rise_m = physics.partPose().translation().z() - part_z0;
  return out;
}

// The cell's 10 g part lifted by the arm at the default 12 s cycle, at the gripper action's grasp pressure.
void printArmLift(const Sweep& s, const std::vector<pf::GripperFinger>& fingers, pf::GraspScene scene,
                  double grasp_pa) {
  scene.object_mass_kg = 0.01;
  const double lift_s = 0.1 * 12.0;  // the lift's tenth of the launch file's default cycle
  const ArmLift lift = armLift(s, fingers, scene, grasp_pa, lift_s);
  std::fprintf(stderr, "grasp_rule_sweep: the arm lifts the 10 g part in %g s at %.0f Pa: tool0 rose %.4f m, the part "
               "%.4f m; during the lift tool z tilted up to %.2f deg and as few as %d fingers touched the part\n",
               lift_s, grasp_pa, lift.tool_rise_m, lift.part_rise_m, lift.largest_tilt_deg, lift.fewest_fingers);
}

void addOptions(CLI::App& app, Sweep& s) {
  app.add_option("--gripper", s.gripper, "the gripper's file")->check(CLI::ExistingFile)->capture_default_str();
  app.add_option("--cell", s.cell, "the cell's file (the part's size, friction, hold margin)")
      ->check(CLI::ExistingFile)->capture_default_str();
  app.add_option("--masses-g", s.masses_g, "the part's masses (g)")->capture_default_str();
  app.add_option("--accelerations", s.accelerations, "the lift's peak accelerations (m/s^2)")->capture_default_str();
  app.add_option("--arm", s.arm, "the arm's URDF (the cell's lift height)")->check(CLI::ExistingFile)
      ->capture_default_str();
  app.add_option("--lift-m", s.lift_m, "how far the lift rises (m; default: the cell's, from --arm and --cell)")
      ->check(CLI::PositiveNumber);
  app.add_option("--timestep-s", s.mjcf.timestep_s, "the engine's step (s)")->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--steps-per-period", s.mjcf.steps_per_period,
                 "the finger joints' armature: steps per period of the stiffest spring (0: none)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  app.add_option("--write-scene", s.scene_out,
                 "also write the first mass's scene, the springs at the grasp pressure, as MJCF to this file "
                 "(mujoco-simulate FILE shows it)");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("grasp_rule_sweep: the cell's grasp rule against MuJoCo, over the part's mass and the lift's "
               "acceleration; one CSV row per case");
  Sweep s;
  addOptions(app, s);
  CLI11_PARSE(app, argc, argv);
  try {
    const std::vector<pf::GripperFinger> fingers = pf::loadGripperFile(s.gripper);
    const CellLift lift = cellLift(s.arm, s.gripper, s.cell);
    if (s.lift_m == 0.0) s.lift_m = lift.height_m;
    if (s.accelerations.empty()) s.accelerations = {0.25, 0.5, 1, 2, 4, 8, lift.fastest_mps2};
    std::fprintf(stderr, "grasp_rule_sweep: the cell lifts tool0 by %.4g m; at its fastest cycle (%g s) the lift's "
                 "peak acceleration is %.4g m/s^2\n", lift.height_m, pf::kMinCycleTimeS, lift.fastest_mps2);
    const CellPart part = readCellPart(s.cell);
    pf::GraspScene scene;
    scene.object_radius_m = part.radius_m;
    scene.object_height_m = part.height_m;
    scene.object_centre_depth_m = pf::sideGraspDepth(fingers, part.radius_m, part.height_m).centre_depth_m;
    const pf::SideGraspForces touch = pf::sideGraspForces(fingers, part.radius_m, part.height_m,
                                                          scene.object_centre_depth_m, 0.0);
    // The gripper action's grasp: the last finger's touch plus the squeeze margin.
    const double gauge_pa = *std::max_element(touch.touch_gauge_pa.begin(), touch.touch_gauge_pa.end()) +
                            s.squeeze_margin_pa;
    const pf::SideGraspForces twin = pf::sideGraspForces(fingers, part.radius_m, part.height_m,
                                                         scene.object_centre_depth_m, gauge_pa);
    printClosedForces(fingers, scene, gauge_pa, twin, s.mjcf);
    printArmLift(s, fingers, scene, gauge_pa);
    std::printf("mass_kg,peak_acceleration_mps2,lift_duration_s,grasp_gauge_pa,twin_normal_force_n,"
                "mujoco_normal_force_n,threshold_mass_kg,cell_rule_holds,rule_with_lift_holds,mujoco_carried,slip_m,"
                "problem\n");
    for (double mass_g : s.masses_g) {
      scene.object_mass_kg = 1e-3 * mass_g;
      if (!s.scene_out.empty() && mass_g == s.masses_g.front()) {
        pf::MjcfOptions at_grasp = s.mjcf;
        at_grasp.gauge_pa = gauge_pa;
        std::ofstream(s.scene_out) << pf::graspSceneMjcf(fingers, scene, at_grasp);
      }
      pf::GraspLiftTrial trial(fingers, scene, s.mjcf);
      for (double a : s.accelerations) {
        pf::LiftMotion lift{s.lift_m, a};
        printRow(scene.object_mass_kg, lift, gauge_pa, twin, part, trial.run(gauge_pa, lift, pf::GraspTrialSettings()));
        std::fflush(stdout);
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "grasp_rule_sweep: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
