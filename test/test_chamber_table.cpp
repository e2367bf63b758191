// The table solver's chamber table (chamber_table.cpp): its measured error within its tolerance, against the
// quad-precision reference on grids the build never saw, for the shipped finger and for others.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "test_support.hpp"

namespace pf = pneumatic_finger;

namespace {
const pf::FingerParameters kPaper = pf::FingerParameters::defaults();
}

TEST(ChamberTable, TableSolverErrorIsMeasuredAndWithinTolerance) {
  pf::ModelOptions options;
  options.solver = pf::SolverKind::kTable;
  pf::FingerModel table(kPaper, options);
  pf::FingerWorkspace table_ws(table);
  EXPECT_GT(table.tableSegmentCount(), 0);
  EXPECT_GT(table.tableMeasuredErrorRad(), 0.0);  // measured, so never exactly 0 for a real interpolant
  EXPECT_LE(table.tableMeasuredErrorRad(), options.table_tolerance_rad);
  // Against the quad reference on a grid the table builder never saw (offset primes), inside its range.
  pf_test::FingerError worst;
  for (double p = 13.0; p <= options.table_max_gauge_pa; p += 997.0) {
    worst.merge(pf_test::fingerError(table.evaluate(p, table_ws), pf_test::referenceFinger(kPaper, p)));
  }
  EXPECT_LE(worst.half_angle_rad, pf_test::kAngleTolerance);
  EXPECT_LE(worst.point_m, pf_test::kPointTolerance);
  RecordProperty("table_max_half_angle_error_rad", pf_test::scientific(worst.half_angle_rad));
  // Outside its range it hands over to the robust solver.
  pf::FingerModel robust(kPaper);
  pf::FingerWorkspace robust_ws(robust);
  EXPECT_EQ(table.evaluate(1e6, table_ws).half_angle_rad[0], robust.evaluate(1e6, robust_ws).half_angle_rad[0]);
}

TEST(ChamberTable, TableSolverHoldsItsBoundForOtherFingers) {
  // The table of identical chambers holds the whole shape (points and theta), one function set per chamber count:
  // 1 and 3 chambers, 20 (above the counts unrolled at compile time), a turning base face, unequal segment lengths;
  // unequal chambers take the table of theta, cos and sin instead. Each against the quad reference, on a grid the
  // builder never saw, inside the table's range.
  std::vector<std::pair<std::string, pf::FingerParameters>> fingers;
  for (int n : {1, 3, 20}) {
    pf::RawParameterMap raw;
    pf::parseParameterAssignment("chamber_count=" + std::to_string(n), raw);
    std::string lengths = "segment_length_m=[";
    for (int i = 0; i < n; ++i) lengths += (i ? "," : "") + std::to_string(0.01 * (1.0 + 0.05 * i));
    pf::parseParameterAssignment(lengths + "]", raw);
    fingers.emplace_back("N = " + std::to_string(n), pf::FingerParameters::fromRaw(raw));
  }
  pf::RawParameterMap turning;
  turning["base_wall_share"] = {{0.3}, false};
  fingers.emplace_back("s0 = 0.3", pf::FingerParameters::fromRaw(turning));
  pf::RawParameterMap unequal;
  unequal["chamber_gap_m"] = {{3e-5, 4e-5, 5e-5, 6e-5, 5e-5, 4e-5, 3e-5}, true};
  fingers.emplace_back("unequal gaps", pf::FingerParameters::fromRaw(unequal));
  for (const auto& [name, params] : fingers) {
    pf::ModelOptions options;
    options.solver = pf::SolverKind::kTable;
    pf::FingerModel table(params, options);
    pf::FingerWorkspace table_ws(table);
    EXPECT_GT(table.tableSegmentCount(), 0) << name;
    EXPECT_LE(table.tableMeasuredErrorRad(), options.table_tolerance_rad) << name;
    pf_test::FingerError worst;
    for (double p = 13.0; p <= options.table_max_gauge_pa; p += 2999.0) {
      worst.merge(pf_test::fingerError(table.evaluate(p, table_ws), pf_test::referenceFinger(params, p)));
    }
    EXPECT_LE(worst.half_angle_rad, pf_test::kAngleTolerance) << name;
    EXPECT_LE(worst.joint_angle_rad, pf_test::kAngleTolerance) << name;
    EXPECT_LE(worst.point_m, pf_test::kPointTolerance) << name;
  }
}
