// "No allocation per evaluation". This test binary replaces the C allocation functions (malloc and its family) with
// counting ones that forward to glibc's own. Everything allocates through them: operator new (libstdc++ calls
// malloc) and Eigen (its dynamic matrices call malloc directly, not operator new). Every solver then evaluates new
// pressures while the count is watched. Not built with the sanitizers, which replace the same functions.
#include <gtest/gtest.h>

#include <Eigen/Core>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);
}

namespace {
std::atomic<long> g_allocations{0};
// Stores through these keep the compiler from eliding the test's own allocations.
std::vector<double>* volatile g_escape_vector;
double* volatile g_escape_data;
}

extern "C" {
void* malloc(std::size_t size) {
  ++g_allocations;
  return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) {
  ++g_allocations;
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t size) {
  ++g_allocations;
  return __libc_realloc(p, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) {
  ++g_allocations;
  return __libc_memalign(alignment, size);
}
void* memalign(std::size_t alignment, std::size_t size) {
  ++g_allocations;
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) {
  ++g_allocations;
  *out = __libc_memalign(alignment, size);
  return *out ? 0 : 12;  // ENOMEM
}
void free(void* p) { __libc_free(p); }
}

namespace pf = pneumatic_finger;

// The counter sees what the model would do if it allocated: both kinds of allocation, each shown to be counted.
TEST(NoAllocation, TheCounterCatchesOperatorNewAndEigen) {
  long before = g_allocations.load();
  g_escape_vector = new std::vector<double>(3);
  delete g_escape_vector;
  EXPECT_GE(g_allocations.load() - before, 2) << "operator new of the vector and of its storage";
  before = g_allocations.load();
  Eigen::VectorXd resized(7);
  resized.resize(64);  // a new size: Eigen frees and mallocs
  g_escape_data = resized.data();
  EXPECT_GE(g_allocations.load() - before, 2) << "Eigen's dynamic vector: construction and resize";
}

TEST(NoAllocation, EvaluationNeverAllocates) {
  pf::RawParameterMap unequal;
  unequal["chamber_gap_m"] = {{1e-5, 2e-5, 3e-5, 4e-5, 5e-5, 6e-5, 7e-5}, true};
  for (const auto& params : {pf::FingerParameters::defaults(), pf::FingerParameters::fromRaw(unequal)}) {
    for (auto solver : {pf::SolverKind::kRobust, pf::SolverKind::kPaper, pf::SolverKind::kTable}) {
      pf::ModelOptions options;
      options.solver = solver;
      pf::FingerModel model(params, options);
      pf::FingerWorkspace ws(model);
      const long before = g_allocations.load();
      double sink = 0;
      for (double p = -1e3; p < 1e6; p += 997) sink += model.evaluate(p, ws).tip().y();
      for (double p : {1e9, 1e300, double(NAN)}) sink += model.evaluate(p, ws).tip().y();
      sink += model.tipAngleAt(2e5);
      EXPECT_EQ(g_allocations.load(), before) << pf::solverName(solver);
      EXPECT_TRUE(std::isfinite(sink) || solver == pf::SolverKind::kPaper);
    }
  }
}
