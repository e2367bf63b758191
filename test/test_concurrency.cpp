// One FingerModel shared by several threads, each with its own FingerWorkspace: every thread gets, bit for bit, what
// it gets alone; and a calibration, whose scan, local solves and leave-one-out folds run on every core.
// scripts/test_sanitized.sh runs this file again under ThreadSanitizer, which reports any access to shared memory that
// is not read-only; here, without it, a workspace shared by mistake would mix the threads' results.
#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <thread>
#include <vector>

#include "pneumatic_finger/calibration/calibration.hpp"
#include "pneumatic_finger/core/finger_model.hpp"

namespace pf = pneumatic_finger;

namespace {

// Unequal chambers use the workspace's scratch (per group and per chamber); identical ones take the inline path.
pf::FingerParameters finger(bool unequal) {
  pf::RawParameterMap raw;
  if (unequal) raw["chamber_gap_m"] = {{1e-5, 2e-5, 3e-5, 4e-5, 5e-5, 6e-5, 7e-5}, true};
  return pf::FingerParameters::fromRaw(raw);
}

// What one thread does with the shared model: evaluate() into its workspace, the const queries, and a batch's
// one-at-a-time path. Each thread walks the pressures from its own offset, so that at any moment they differ.
struct ThreadResult {
  std::vector<double> tip_y_m, tip_angle_rad, batch_tip_angle_rad;
};

ThreadResult work(const pf::FingerModel& model, const std::vector<double>& pressures, std::size_t offset) {
  pf::FingerWorkspace workspace(model);
  ThreadResult r;
  const std::size_t n = pressures.size();
  for (std::size_t k = 0; k < n; ++k) {
    const double p = pressures[(k + offset) % n];
    r.tip_y_m.push_back(model.evaluate(p, workspace).tip().y());
    r.tip_angle_rad.push_back(model.tipAngleAt(p));
  }
  r.batch_tip_angle_rad.resize(n);
  pf::BatchOutputs out;
  out.tip_angle_rad = r.batch_tip_angle_rad.data();
  model.evaluateMany(pressures.data(), n, out, workspace, pf::BatchPath::kScalar);
  return r;
}

void expectEveryThreadAsAlone(const pf::FingerModel& model, const std::string& what) {
  std::vector<double> pressures;
  for (int i = 0; i < 400; ++i) pressures.push_back(750.0 * i);
  constexpr std::size_t kThreads = 4;
  std::vector<ThreadResult> alone, together(kThreads);
  for (std::size_t t = 0; t < kThreads; ++t) alone.push_back(work(model, pressures, 97 * t));
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] { together[t] = work(model, pressures, 97 * t); });
  }
  for (auto& thread : threads) thread.join();
  for (std::size_t t = 0; t < kThreads; ++t) {
    EXPECT_EQ(together[t].tip_y_m, alone[t].tip_y_m) << what << ", thread " << t;
    EXPECT_EQ(together[t].tip_angle_rad, alone[t].tip_angle_rad) << what << ", thread " << t;
    EXPECT_EQ(together[t].batch_tip_angle_rad, alone[t].batch_tip_angle_rad) << what << ", thread " << t;
  }
}

}  // namespace

TEST(Concurrency, ThreadsSharingOneModelEachWithItsWorkspaceGetWhatTheyGetAlone) {
  for (bool unequal : {false, true}) {
    for (auto solver : {pf::SolverKind::kRobust, pf::SolverKind::kTable, pf::SolverKind::kPaper}) {
      pf::ModelOptions options;
      options.solver = solver;
      const pf::FingerModel model(finger(unequal), options);
      expectEveryThreadAsAlone(model, std::string(pf::solverName(solver)) + (unequal ? ", unequal" : ", identical"));
    }
  }
}

TEST(Concurrency, AWorkspaceOfAnotherShapeIsRefusedNamingBoth) {
  const pf::FingerModel unequal(finger(true)), identical(finger(false));
  pf::FingerWorkspace for_identical(identical);
  try {
    unequal.evaluate(1e5, for_identical);
    FAIL() << "a workspace sized for 1 group was accepted by a model of 7";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("7 chambers in 1 groups, not this one's 7 in 7"), std::string::npos)
        << e.what();
  }
}

// The calibration runs its scan's points, its local solves and leave-one-out's folds on every core
// (src/calibration/every_core.hpp), each task writing its own slot, combined in order. Under ThreadSanitizer any
// other shared write is reported; here, two runs, whose threads interleave as they happen to, give the same bits.
TEST(Concurrency, ACalibrationOnEveryCoreGivesTheSameBitsEveryRun) {
  const std::vector<pf::Measurement> data =
      pf::readMeasurementsCsv(std::string(PACKAGE_SOURCE_DIR) + "/data/sierra2022_table1.csv", 4);
  const auto run = [&data] {
    return pf::calibrateWallLaws(pf::FingerParameters::defaults(), {pf::WallLaw::kPaper},
                                 {"shear_modulus_pa", "chamber_gap_m"}, data, pf::CalibrationObjective::kMinimax,
                                 pf::CalibrationQuantity::kOuterAverage, {});
  };
  const auto first = run(), second = run();
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].fit.values, second[0].fit.values);
  ASSERT_EQ(first[0].leave_one_out.size(), data.size());
  for (std::size_t i = 0; i < data.size(); ++i) {
    EXPECT_EQ(first[0].leave_one_out[i].model_joint_rad, second[0].leave_one_out[i].model_joint_rad) << "row " << i;
  }
}
