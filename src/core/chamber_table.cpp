// The chamber table's build (chamber_table.hpp): Chebyshev interpolation per segment, converted to monomials, with
// segments doubling until the error measured against the robust solver meets ModelOptions::table_tolerance_rad.
#include "chamber_table.hpp"

#include <array>
#include <vector>

#include "pneumatic_finger/core/units.hpp"
#include "uniform_shape.hpp"

namespace pneumatic_finger {

namespace {

// The kTableNodes first-kind Chebyshev nodes on [-1, 1].
double chebyshevNode(int j) { return std::cos(kPi * (j + 0.5) / kTableNodes); }

// The interpolant through @p values (taken at the Chebyshev nodes) as monomial coefficients (index = power).
// Degree 7 keeps the conversion well conditioned (|coefficients| grow by < 2^7).
std::array<double, kTableNodes> monomialInterpolant(const std::array<double, kTableNodes>& values) {
  using Square = std::array<std::array<double, kTableNodes>, kTableNodes>;
  // T_k at the nodes, and the monomial coefficients of T_k (by T_{k+1} = 2x T_k - T_{k-1}): the same for every
  // segment and function, so computed once (the cosines were most of a table's build time).
  static const Square kChebyshevAtNodes = [] {
    Square c{};
    for (int k = 0; k < kTableNodes; ++k) {
      for (int j = 0; j < kTableNodes; ++j) c[k][j] = std::cos(kPi * k * (j + 0.5) / kTableNodes);
    }
    return c;
  }();
  static const Square t = [] {
    Square m{};
    m[0][0] = 1.0;
    m[1][1] = 1.0;
    for (int k = 1; k + 1 < kTableNodes; ++k) {
      for (int i = 0; i < kTableNodes; ++i) m[k + 1][i] = (i > 0 ? 2.0 * m[k][i - 1] : 0.0) - m[k - 1][i];
    }
    return m;
  }();
  std::array<double, kTableNodes> cheb{};
  for (int k = 0; k < kTableNodes; ++k) {
    double sum = 0.0;
    for (int j = 0; j < kTableNodes; ++j) sum += values[j] * kChebyshevAtNodes[k][j];
    cheb[k] = (k == 0 ? 1.0 : 2.0) * sum / kTableNodes;
  }
  std::array<double, kTableNodes> mono{};
  for (int k = 0; k < kTableNodes; ++k) {
    for (int i = 0; i < kTableNodes; ++i) mono[i] += cheb[k] * t[k][i];
  }
  return mono;
}

}  // namespace

int FingerModel::tableSegmentCount() const {
  int most = 0;
  for (const auto& g : groups_) most = std::max(most, g.table_segments);
  return most;
}

// The functions a table row interpolates, at u = sqrt(P), from the robust chain: theta, then for a shape table the
// points O_2..O_{N+1} that evaluate() writes from theta (@p scratch holds them), else cos and sin.
void FingerModel::exactTableFunctions(const ChamberGroup& group, double u, FingerState& scratch, double* f) const {
  const HalfAngle h = solveRobust(group, u * u, parameters_.atmospheric_pressure_pa).half;
  f[0] = h.rad;
  if (group.table_functions == kTableTrigFunctions) {
    f[1] = h.cos;
    f[2] = h.sin;
    return;
  }
  const int n = parameters_.chamber_count;
  uniformWriterFor(n)(parameters_, first_joint_series_, false, 1.0, 0.0, h.rad, h.cos, h.sin, h.tan, scratch);
  std::copy(scratch.backbone_m.data() + 4, scratch.backbone_m.data() + 4 + 2 * n, f + 1);
}

// @p group's table with @p segments segments on [u_begin, u_end]: per segment, the interpolant of every function
// through its values at the Chebyshev nodes (one solve per node gives every function), as monomial coefficients.
void FingerModel::interpolateTable(ChamberGroup& group, double u_begin, double u_end, int segments,
                                   FingerState& scratch) const {
  const int functions = group.table_functions;
  const double width = (u_end - u_begin) / segments;
  std::vector<double> at(static_cast<std::size_t>(functions) * kTableNodes);
  group.table.assign(static_cast<std::size_t>(segments) * functions * kTableNodes, 0.0);
  group.table_theta_only.resize(static_cast<std::size_t>(segments) * kTableNodes);
  for (int s = 0; s < segments; ++s) {
    const double u0 = u_begin + s * width;
    for (int j = 0; j < kTableNodes; ++j) {
      exactTableFunctions(group, u0 + 0.5 * (chebyshevNode(j) + 1.0) * width, scratch, &at[j * functions]);
    }
    double* row = &group.table[static_cast<std::size_t>(s) * functions * kTableNodes];
    for (int f = 0; f < functions; ++f) {
      std::array<double, kTableNodes> values;
      for (int j = 0; j < kTableNodes; ++j) values[static_cast<std::size_t>(j)] = at[j * functions + f];
      const auto coefficients = monomialInterpolant(values);
      for (int i = 0; i < kTableNodes; ++i) row[i * functions + f] = coefficients[static_cast<std::size_t>(i)];
    }
    // theta (function 0) again on its own, for the callers that want theta alone.
    for (int i = 0; i < kTableNodes; ++i) {
      group.table_theta_only[static_cast<std::size_t>(s * kTableNodes + i)] = row[i * functions];
    }
  }
  group.table_u_begin = u_begin;
  group.table_u_end = u_end;
  group.table_inv_width = 1.0 / width;
  group.table_segments = segments;
}

// Measure, do not assume: the largest difference between what evaluate() publishes from @p group's table and the
// robust solver, at 9 interior points of every segment (none of them an interpolation node) plus both ends. A point
// error of e metres counts as e / length radians (the turn at the base that moves the tip as far), so that one
// tolerance in radians bounds both.
double FingerModel::tableErrorRad(const ChamberGroup& group, FingerState& exact_state, FingerState& table_state) const {
  const int n = parameters_.chamber_count;
  const double length_m = parameters_.lengthM();
  const double width = (group.table_u_end - group.table_u_begin) / group.table_segments;  // as interpolateTable
  std::vector<double> want(static_cast<std::size_t>(group.table_functions));
  double error = 0.0;
  for (int s = 0; s < group.table_segments; ++s) {
    for (int j = 0; j <= 10; ++j) {
      const double u = group.table_u_begin + (s + j / 10.0) * width;
      const double p = u * u;
      exactTableFunctions(group, u, exact_state, want.data());
      if (group.table_functions == kTableTrigFunctions) {
        const ChamberGroupSolution got = solveGroup(group, p, false);
        error = std::max({error, std::fabs(got.half.rad - want[0]), std::fabs(got.half.cos - want[1]),
                          std::fabs(got.half.sin - want[2])});
        continue;
      }
      int segment = 0;
      double x = 0.0;
      if (!tableSegment(group, p, segment, x) ||
          !table_shape_writer_(parameters_, table_polynomials_, tableRow(group, segment), x, false, 1.0, 0.0,
                               table_state)) {
        continue;  // at contact itself, or a theta a rounding below 0: evaluate() gives the rest shape there
      }
      error = std::max(error, std::fabs(table_state.half_angle_rad[0] - want[0]));
      for (int k = 0; k < 2 * n; ++k) {
        error = std::max(error, std::fabs(table_state.backbone_m.data()[4 + k] - want[1 + k]) / length_m);
      }
    }
  }
  return error;
}

// Identical chambers: the table holds the published shape itself (points and theta), so that evaluate() runs no stage
// after the lookup. Unequal chambers: theta, cos and sin per group, composed by jointsAndBackbone. The segments double
// until the measured error meets the tolerance.
void FingerModel::buildTable(ChamberGroup& group) {
  const double u_begin = std::sqrt(group.contact_gauge_pa);
  const double u_end = std::sqrt(options_.table_max_gauge_pa);
  if (!(u_end > u_begin)) return;  // never in contact within the table's range: theta = 0 or robust above
  group.table_functions = groups_.size() == 1 ? tableShapeFunctions(parameters_.chamber_count) : kTableTrigFunctions;
  FingerState exact_state = restState(parameters_), table_state = exact_state;
  double achieved = 0.0;
  for (int segments = 8; segments <= kTableMaxSegments; segments *= 2) {
    interpolateTable(group, u_begin, u_end, segments, exact_state);
    achieved = tableErrorRad(group, exact_state, table_state);
    if (achieved <= options_.table_tolerance_rad) break;
  }
  table_error_rad_ = std::max(table_error_rad_, achieved);
}

}  // namespace pneumatic_finger
