// sim_bench: the finger in MuJoCo, one step with and without the twin's springs rewritten for that step's pressure,
// and a step of the whole cell (docs/SIMULATION.md). Side by side in one run: the springs' share of a step is the
// difference. The counter real_time_factor is simulated time per wall time (the file's step over its cost).
#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <fstream>
#include <stdexcept>
#include <string>

#include <yaml-cpp/yaml.h>

#include <vector>

#include "pneumatic_finger/cell/side_grasp.hpp"
#include "pneumatic_finger/core/regulator.hpp"
#include "pneumatic_finger/sim/cell_physics.hpp"
#include "pneumatic_finger/sim/finger_mjcf.hpp"
#include "pneumatic_finger/sim/pressure_driven_finger.hpp"

namespace pf = pneumatic_finger;

namespace {

struct Sim {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  Sim() {
    const std::string path = "/tmp/pneumatic_finger_sim_bench.xml";
    std::ofstream(path) << pf::fingerMjcf(pf::FingerParameters::defaults(), pf::FingerUrdfOptions(), pf::MjcfOptions());
    char error[1000] = "";
    m = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
    if (!m) throw std::runtime_error(error);
    d = mj_makeData(m);
  }
  ~Sim() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
};

// A fill and a release of 1 kg/cm^2 every 0.2 s of simulated time: every step has a new pressure.
double gaugeAt(double t) {
  const double phase = t / 0.2 - static_cast<int>(t / 0.2);
  return 98066.5 * (phase < 0.5 ? 2.0 * phase : 2.0 - 2.0 * phase);
}

void benchStep(benchmark::State& state, bool springs) {
  Sim sim;
  const pf::FingerModel twin(pf::FingerParameters::defaults());
  pf::PressureDrivenFinger finger(twin, sim.m, "finger_");
  std::string why;
  for (auto _ : state) {
    if (springs) finger.applyPressure(gaugeAt(sim.d->time), why);
    mj_step(sim.m, sim.d);
  }
  state.counters["real_time_factor"] =
      benchmark::Counter(sim.m->opt.timestep * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.SetLabel(springs ? "one finger, springs rewritten every step" : "one finger, springs fixed");
}

// The whole cell (config/cell.yaml, config/gripper.yaml, urdf/industrial_arm.urdf): the arm held at the pick pose by
// its position actuators, the three fingers filled at the regulator's rate to 1 kg/cm^2 (beyond the part's touch, at
// about 0.82 kg/cm^2) and held there, the 10 g part on its table: every step writes every finger's springs with the
// held moments (applyPressureWithHeldMoments) and steps the engine on the file's step.
void benchCell(benchmark::State& state) {
  const std::string root = PACKAGE_SOURCE_DIR;
  const YAML::Node cell = YAML::LoadFile(root + "/config/cell.yaml");
  const std::vector<pf::GripperFinger> fingers = pf::loadGripperFile(root + "/config/gripper.yaml");
  pf::GraspScene scene;
  scene.object_centre_depth_m = pf::sideGraspDepth(fingers, scene.object_radius_m, scene.object_height_m).centre_depth_m;
  pf::CellPhysics physics(pf::readRobotUrdfFile(root + "/urdf/industrial_arm.urdf"), fingers,
                          cell["arm_joint_names"].as<std::vector<std::string>>(),
                          cell["pick"].as<std::vector<double>>(), scene, pf::MjcfOptions());
  const double rate = pf::gripperFillRatePaPerS(pf::kCellRegulatorFlowM3PerS, fingers.front().parameters, 3);
  const double dt = physics.model().opt.timestep;
  double gauge = 0.0;
  std::string why;
  for (auto _ : state) {
    gauge = pf::regulatorStep(gauge, 98066.5, rate, dt);
    if (!physics.step(gauge, why)) state.SkipWithError(why.c_str());
  }
  state.counters["real_time_factor"] = benchmark::Counter(dt * static_cast<double>(state.iterations()),
                                                          benchmark::Counter::kIsRate);
  state.counters["contacts"] = physics.data().ncon;
  state.SetLabel("the cell: arm, 3 fingers with held moments rewritten every step, the part; " +
                 pf::formatShortest(1e3 * dt) + " ms step");
}

}  // namespace

BENCHMARK(benchCell)->Name("sim/cell_step");
BENCHMARK_CAPTURE(benchStep, fixed_springs, false)->Name("sim/step");
BENCHMARK_CAPTURE(benchStep, twin_springs, true)->Name("sim/step_with_springs");
BENCHMARK_MAIN();
