// "No allocation per evaluation": global operator new is replaced by a counting one in this test binary, and
// every solver evaluates new pressures while the count is watched.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <vector>
#include <new>

#include "pneumatic_finger/core/finger_model.hpp"

namespace {
std::atomic<long> g_allocations{0};
}

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace pf = pneumatic_finger;

TEST(NoAllocation, EvaluationNeverAllocates) {
  pf::RawParameterMap unequal;
  unequal["chamber_gap_m"] = {{1e-5, 2e-5, 3e-5, 4e-5, 5e-5, 6e-5, 7e-5}, true};
  for (const auto& params : {pf::FingerParameters::defaults(), pf::FingerParameters::fromRaw(unequal)}) {
    for (auto solver : {pf::SolverKind::kRobust, pf::SolverKind::kPaper, pf::SolverKind::kTable}) {
      pf::ModelOptions options;
      options.solver = solver;
      pf::FingerModel model(params, options);
      const long before = g_allocations.load();
      double sink = 0;
      for (double p = -1e3; p < 1e6; p += 997) sink += model.evaluate(p).tip().y();
      for (double p : {1e9, 1e300, double(NAN)}) sink += model.evaluate(p).tip().y();
      sink += model.tipAngleAt(2e5);
      EXPECT_EQ(g_allocations.load(), before) << pf::solverName(solver);
      EXPECT_TRUE(std::isfinite(sink) || solver == pf::SolverKind::kPaper);
    }
  }
  // The counter itself works (else the test could not fail).
  const long before = g_allocations.load();
  auto* v = new std::vector<double>(3);
  delete v;
  EXPECT_GT(g_allocations.load(), before);
}
