// sim_bench: the finger in MuJoCo, one step with and without the twin's springs rewritten for that step's pressure
// (docs/SIMULATION.md). Side by side in one run: the springs' share of a step is the difference. The counter
// real_time_factor is simulated time per wall time (the step's 0.1 ms over its cost).
#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <fstream>
#include <stdexcept>
#include <string>

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

}  // namespace

BENCHMARK_CAPTURE(benchStep, fixed_springs, false)->Name("sim/step");
BENCHMARK_CAPTURE(benchStep, twin_springs, true)->Name("sim/step_with_springs");
BENCHMARK_MAIN();
