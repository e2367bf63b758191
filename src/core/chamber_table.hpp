// The table solver's chamber table: piecewise degree-7 polynomials in u = sqrt(P) from contact to
// ModelOptions::table_max_gauge_pa, built and measured at construction (chamber_table.cpp), and looked up by the
// evaluation (finger_model.cpp). For identical chambers a row holds the published shape itself (theta, then the
// points O_2..O_{N+1}); for unequal chambers theta, cos theta, sin theta per group. Internal header of src/core.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "pneumatic_finger/core/finger_model.hpp"
#include "table_kernel.hpp"

namespace pneumatic_finger {

constexpr int kTableDegree = 7;                   // per-segment polynomial degree
constexpr int kTableNodes = kTableDegree + 1;     // Chebyshev nodes per segment
// Unequal chambers: theta, cos theta, sin theta. Identical chambers: theta, the 2 N point coordinates, and zeros up to
// whole packs of the widest SIMD variant (table_kernel.hpp).
constexpr int kTableTrigFunctions = 3;
constexpr int tableShapeFunctions(int chamber_count) {
  return (2 * chamber_count + 1 + kTablePackFunctions - 1) / kTablePackFunctions * kTablePackFunctions;
}
constexpr int kTableMaxSegments = 4096;

// Estrin's scheme for one of a segment's degree-7 polynomials (coefficient i of function f at
// row[i * functions + f]): pairs, then x^2 and x^4 combine them, three levels of independent products instead of
// Horner's chain of seven (the chain was the table's latency).
static_assert(kTableDegree == 7, "the table's Estrin schemes are written for degree 7");
inline double tableFunction(const double* row, int functions, int f, double x) {
  const double x2 = x * x, x4 = x2 * x2;
  auto c = [row, functions, f](int i) { return row[i * functions + f]; };
  const double p01 = c(0) + c(1) * x, p23 = c(2) + c(3) * x, p45 = c(4) + c(5) * x, p67 = c(6) + c(7) * x;
  return (p01 + p23 * x2) + (p45 + p67 * x2) * x4;
}

// Where @p gauge_pa falls in the table: the segment, and x in [-1, 1] within it.
inline bool FingerModel::tableSegment(const ChamberGroup& group, double gauge_pa, int& segment, double& x) {
  if (!(gauge_pa > group.contact_gauge_pa) || group.table_segments == 0) return false;
  const double u = std::sqrt(gauge_pa);
  if (!(u <= group.table_u_end)) return false;
  const double pos = (u - group.table_u_begin) * group.table_inv_width;
  int s = static_cast<int>(pos);
  s = std::min(std::max(s, 0), group.table_segments - 1);
  x = 2.0 * (pos - s) - 1.0;
  segment = s;
  return true;
}

inline const double* FingerModel::tableRow(const ChamberGroup& group, int segment) {
  const auto stride = static_cast<std::size_t>(group.table_functions) * kTableNodes;
  return &group.table[static_cast<std::size_t>(segment) * stride];
}

// The same coefficients as the row's theta, in the same order of operations: the same bits as evaluate().
inline double FingerModel::tableTheta(const ChamberGroup& group, int segment, double x) {
  return tableFunction(&group.table_theta_only[static_cast<std::size_t>(segment) * kTableNodes], 1, 0, x);
}

}  // namespace pneumatic_finger
