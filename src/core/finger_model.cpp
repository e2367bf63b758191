#include "pneumatic_finger/core/finger_model.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "pneumatic_finger/core/units.hpp"
#include "batch_kernel.hpp"
#include "table_kernel.hpp"

namespace pneumatic_finger {

namespace {

constexpr int kTableDegree = 7;                   // per-segment polynomial degree
constexpr int kTableNodes = kTableDegree + 1;     // Chebyshev nodes per segment
// Unequal chambers: theta, cos theta, sin theta. Identical chambers: theta, the 2 N point coordinates, and zeros up to
// whole packs of the widest SIMD variant (table_kernel.hpp).
constexpr int kTableTrigFunctions = 3;
constexpr int tableShapeFunctions(int chamber_count) {
  return (2 * chamber_count + 1 + kTablePackFunctions - 1) / kTablePackFunctions * kTablePackFunctions;
}
constexpr int kTableMaxSegments = 4096;

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

// The table's polynomials for the widest instruction set this CPU has (as the batch picks its kernel).
TablePolynomials widestTablePolynomials() {
#if defined(__x86_64__)
  if (batchPathAvailable(BatchPath::kAvx512)) return tablePolynomialsAvx512;
  if (batchPathAvailable(BatchPath::kAvx2)) return tablePolynomialsAvx2;
#endif
  return tablePolynomialsGeneric;
}

// Stages 5-6 for identical chambers: q_1 = theta_0 + theta, q_n = 2 theta, and nothing per chamber needs to be looked
// up or copied. kChambers > 0 is the chamber count as a compile-time constant, so that the compiler unrolls the loops
// over the chambers (their control cost as much as their arithmetic); 0 takes it from the parameters.

// The four per-chamber columns, the tip direction and the contact flag, from theta and q_1.
template <int kChambers>
__attribute__((always_inline)) inline void uniformColumns(int n, bool detail, double stretch, double bulge_m,
                                                          double theta, double q1, FingerState& out) {
  const double q = 2.0 * theta;
  // With the count known at compile time, two numbers per store (a fixed-size map, which Eigen writes in packets);
  // otherwise one plain loop (four run-time setConstant calls cost more than the stores). Distinct arrays:
  // __restrict spares the compiler's run-time checks for overlap, which cost more than the stores.
  double* __restrict stretch_out = out.stretch.data();
  double* __restrict bulge_out = out.bulge_m.data();
  double* __restrict half_out = out.half_angle_rad.data();
  double* __restrict joint_out = out.joint_angle_rad.data();
  if constexpr (kChambers > 0) {
    using Column = Eigen::Map<Eigen::Matrix<double, kChambers, 1>, Eigen::Unaligned>;
    if (detail) {
      Column(stretch_out).setConstant(stretch);
      Column(bulge_out).setConstant(bulge_m);
    }
    Column(half_out).setConstant(theta);
    Column(joint_out).setConstant(q);
  } else {
    for (int i = 0; i < n; ++i) {
      if (detail) {
        stretch_out[i] = stretch;
        bulge_out[i] = bulge_m;
      }
      half_out[i] = theta;
      joint_out[i] = q;
    }
  }
  joint_out[0] = q1;
  out.tip_angle_rad = q1 + (n - 1) * q;
  out.walls_in_contact = theta > 0.0;
}

// O_0 and O_1: the base segment's ends, the same for every pressure.
inline void basePoints(const FingerParameters& parameters, double* __restrict points) {
  points[0] = 0.0;
  points[1] = 0.0;
  points[2] = parameters.base_segment_length_m;
  points[3] = 0.0;
}

// The shape from the half angle: firstJoint and uniformPoints (simd_math.hpp) are shared with the batch kernel, so
// that both round alike. theta and its cosine, sine and tangent come as four numbers, not a HalfAngle: in registers,
// not through memory (a struct's fields stored by one function and loaded by the next wait for each other).
template <int kChambers>
void jointsAndBackboneUniform(const FingerParameters& parameters, const FirstJointSeries& series, bool detail,
                              double stretch, double bulge_m, double theta, double cos_half, double sin_half,
                              double tan_half, FingerState& out) {
  const int n = kChambers > 0 ? kChambers : parameters.chamber_count;
  double* __restrict points = out.backbone_m.data();  // column-major 2 x (N+2)
  basePoints(parameters, points);
  double first_c, first_s;
  const double q1 =
      firstJoint(parameters.base_wall_share, series, theta, tan_half, cos_half, sin_half, first_c, first_s);
  std::array<double, kMaxChamberCount> dir_c, dir_s;
  uniformPoints<kChambers>(first_c, first_s, cos_half, sin_half, n, parameters.base_segment_length_m,
                           parameters.segment_length_m.data(), dir_c.data(), dir_s.data(), points + 4, points + 5, 2);
  uniformColumns<kChambers>(n, detail, stretch, bulge_m, theta, q1, out);
}

// The shape from the table of identical chambers (row: the segment, x in [-1, 1]): theta and the points are its
// polynomials (@p polynomials: the widest SIMD variant, table_kernel.hpp), so nothing of stages 4-6 runs. They are
// written straight into the state's backbone from O_1's y on (theta there, then O_2..O_{N+1}), not into a buffer that
// is then copied: the copy's loads of the polynomials' fresh vector stores cost more than the polynomials' own stores.
// basePoints then writes O_0 and O_1 over theta.
// @return false for a theta a rounding error below 0 (the interpolant next to contact), where the caller writes the
// rest shape over the points written here.
template <int kChambers>
bool tableShape(const FingerParameters& parameters, TablePolynomials polynomials, const double* row, double x,
                bool detail, double stretch, double bulge_m, FingerState& out) {
  const int n = kChambers > 0 ? kChambers : parameters.chamber_count;
  double* __restrict points = out.backbone_m.data();  // column-major 2 x (N+2)
  polynomials(row, tableShapeFunctions(n), 2 * n + 1, x, points + 3);
  const double theta = points[3];
  if (!(theta >= 0.0)) return false;
  basePoints(parameters, points);
  uniformColumns<kChambers>(n, detail, stretch, bulge_m, theta, firstJointAngle(parameters.base_wall_share, theta),
                            out);
  return true;
}

// One instance per chamber count up to kUnrolledChambers (the fingers people build have a handful to a dozen
// chambers), the run-time count above.
constexpr int kUnrolledChambers = 16;
template <class Writer, template <int> class Pick, std::size_t... kCounts>
constexpr std::array<Writer, sizeof...(kCounts)> writersFor(std::index_sequence<kCounts...>) {
  return {Pick<static_cast<int>(kCounts)>::value...};
}
template <class Writer, template <int> class Pick>
Writer writerFor(int chamber_count) {
  static constexpr std::array<Writer, kUnrolledChambers + 1> kWriters =
      writersFor<Writer, Pick>(std::make_index_sequence<kUnrolledChambers + 1>{});
  return kWriters[static_cast<std::size_t>(chamber_count <= kUnrolledChambers ? chamber_count : 0)];
}

using UniformWriter = void (*)(const FingerParameters&, const FirstJointSeries&, bool, double, double, double, double,
                               double, double, FingerState&);
template <int kChambers>
struct PickUniform {
  static constexpr UniformWriter value = &jointsAndBackboneUniform<kChambers>;
};
UniformWriter uniformWriterFor(int chamber_count) { return writerFor<UniformWriter, PickUniform>(chamber_count); }

using TableShapeWriter = bool (*)(const FingerParameters&, TablePolynomials, const double*, double, bool, double,
                                  double, FingerState&);
template <int kChambers>
struct PickTableShape {
  static constexpr TableShapeWriter value = &tableShape<kChambers>;
};
TableShapeWriter tableShapeWriterFor(int chamber_count) {
  return writerFor<TableShapeWriter, PickTableShape>(chamber_count);
}

}  // namespace

const char* solverName(SolverKind kind) {
  switch (kind) {
    case SolverKind::kRobust: return "robust";
    case SolverKind::kPaper: return "paper";
    case SolverKind::kTable: return "table";
  }
  return "robust";
}

SolverKind parseSolverName(const std::string& name) {
  for (SolverKind k : {SolverKind::kRobust, SolverKind::kPaper, SolverKind::kTable}) {
    if (name == solverName(k)) return k;
  }
  throw ParameterError("unknown solver '" + name + "'; known solvers: robust, paper, table");
}

double gaugeForBulge(double bulge_m, double chamber_height_m, double shear_modulus_pa, double atmospheric_pa) {
  if (!(bulge_m > 0.0)) return 0.0;
  // Stage 3 inverted: sqrt(2 lambda^2 - 1) = 1 + x with x = 2h/L, so lambda^2 - 1 = x (2 + x)/2.
  const double x = 2.0 * bulge_m / chamber_height_m;
  const double lambda_sq_m1 = 0.5 * x * (2.0 + x);
  const double delta = lambda_sq_m1 / (std::sqrt(1.0 + lambda_sq_m1) + 1.0);
  // Stage 2 inverted: g = delta^2 (3 + delta)/(1 + delta).
  const double g = delta * delta * (3.0 + delta) / (1.0 + delta);
  // Stage 1 inverted: P^2 + 2 P_o P - g P_o mu = 0, positive root without cancellation.
  const double gpm = g * atmospheric_pa * shear_modulus_pa;
  return gpm / (atmospheric_pa + std::sqrt(atmospheric_pa * atmospheric_pa + gpm));
}

double contactGaugePa(double chamber_height_m, double chamber_gap_m, double shear_modulus_pa,
                      double atmospheric_pa) {
  return gaugeForBulge(chamber_gap_m, chamber_height_m, shear_modulus_pa, atmospheric_pa);
}

FingerModel::FingerModel(const FingerParameters& parameters, const ModelOptions& options)
    : parameters_(parameters), options_(options), first_joint_series_(firstJointSeries(parameters.base_wall_share)) {
  const int n = parameters_.chamber_count;
  group_of_chamber_.resize(static_cast<std::size_t>(n));
  contact_gauge_pa_ = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    ChamberGroup g{parameters_.chamber_height_m[k], parameters_.wall_critical_height_m[k],
                   parameters_.chamber_gap_m[k], parameters_.shear_modulus_pa[k], 0.0, {}, 0, 0, 0, 0, 0, {}};
    auto same = [&g](const ChamberGroup& o) {
      return o.chamber_height_m == g.chamber_height_m && o.wall_critical_height_m == g.wall_critical_height_m &&
             o.chamber_gap_m == g.chamber_gap_m && o.shear_modulus_pa == g.shear_modulus_pa;
    };
    auto it = std::find_if(groups_.begin(), groups_.end(), same);
    if (it == groups_.end()) {
      g.contact_gauge_pa = pneumatic_finger::contactGaugePa(g.chamber_height_m, g.chamber_gap_m, g.shear_modulus_pa,
                                          parameters_.atmospheric_pressure_pa);
      groups_.push_back(g);
      it = groups_.end() - 1;
    }
    group_of_chamber_[k] = static_cast<int>(it - groups_.begin());
    contact_gauge_pa_ = std::min(contact_gauge_pa_, it->contact_gauge_pa);
  }
  if (options_.solver == SolverKind::kTable) {
    if (groups_.size() == 1) {
      table_shape_writer_ = tableShapeWriterFor(n);
      table_polynomials_ = widestTablePolynomials();
    }
    for (auto& g : groups_) buildTable(g);
  }
  shape_ = static_cast<std::uint64_t>(n) << 32 | static_cast<std::uint64_t>(groups_.size());
}

FingerWorkspace::FingerWorkspace(const FingerModel& model)
    : shape_(model.shape_),
      state_(model.initialState()),
      group_solutions_(model.groups_.size()),
      chamber_half_(static_cast<std::size_t>(model.chamberCount())) {}

// Out of line and cold, so that evaluate()'s check stays one comparison of two numbers.
[[noreturn]] __attribute__((noinline, cold)) void FingerModel::refuseWorkspace(const FingerWorkspace& workspace) const {
  throw std::invalid_argument("FingerModel: the workspace was made for a model of " +
                              std::to_string(workspace.chamber_half_.size()) + " chambers in " +
                              std::to_string(workspace.group_solutions_.size()) + " groups, not this one's " +
                              std::to_string(group_of_chamber_.size()) + " in " + std::to_string(groups_.size()));
}

int FingerModel::tableSegmentCount() const {
  int most = 0;
  for (const auto& g : groups_) most = std::max(most, g.table_segments);
  return most;
}

void FingerModel::buildTable(ChamberGroup& group) {
  const double u_begin = std::sqrt(group.contact_gauge_pa);
  const double u_end = std::sqrt(options_.table_max_gauge_pa);
  if (!(u_end > u_begin)) return;  // never in contact within the table's range: theta = 0 or robust above
  const int n = parameters_.chamber_count;
  // Identical chambers: the table holds the published shape itself (points and theta), so that evaluate() runs
  // no stage after the lookup. Unequal chambers: theta, cos and sin per group, composed by jointsAndBackbone.
  const bool shape = groups_.size() == 1;
  const int functions = shape ? tableShapeFunctions(n) : kTableTrigFunctions;
  group.table_functions = functions;
  // The finger's length: a point error of e metres counts as e / length radians (the turn at the base that moves
  // the tip as far), so that one tolerance in radians bounds both.
  double length_m = parameters_.base_segment_length_m;
  for (double z : parameters_.segment_length_m) length_m += z;
  FingerState exact_state = restState(parameters_), table_state = exact_state;
  // The exact functions at u: the robust chain, and for identical chambers the backbone evaluate() writes from it.
  auto exact = [&](double u, double* f) {
    const HalfAngle h = solveRobust(group, u * u, parameters_.atmospheric_pressure_pa).half;
    if (shape) {
      uniformWriterFor(n)(parameters_, first_joint_series_, false, 1.0, 0.0, h.rad, h.cos, h.sin, h.tan, exact_state);
      f[0] = h.rad;
      std::copy(exact_state.backbone_m.data() + 4, exact_state.backbone_m.data() + 4 + 2 * n, f + 1);
    } else {
      f[0] = h.rad;
      f[1] = h.cos;
      f[2] = h.sin;
    }
  };
  std::vector<double> at(static_cast<std::size_t>(functions) * kTableNodes), want(static_cast<std::size_t>(functions));
  double achieved = 0.0;
  for (int segments = 8; segments <= kTableMaxSegments; segments *= 2) {
    const double width = (u_end - u_begin) / segments;
    group.table.assign(static_cast<std::size_t>(segments) * functions * kTableNodes, 0.0);
    for (int s = 0; s < segments; ++s) {
      const double u0 = u_begin + s * width;
      // One solve per node gives every function together.
      for (int j = 0; j < kTableNodes; ++j) exact(u0 + 0.5 * (chebyshevNode(j) + 1.0) * width, &at[j * functions]);
      double* row = &group.table[static_cast<std::size_t>(s) * functions * kTableNodes];
      for (int f = 0; f < functions; ++f) {
        std::array<double, kTableNodes> values;
        for (int j = 0; j < kTableNodes; ++j) values[static_cast<std::size_t>(j)] = at[j * functions + f];
        const auto coefficients = monomialInterpolant(values);
        for (int i = 0; i < kTableNodes; ++i) row[i * functions + f] = coefficients[static_cast<std::size_t>(i)];
      }
    }
    group.table_theta_only.resize(static_cast<std::size_t>(segments) * kTableNodes);
    for (int s = 0; s < segments; ++s) {
      for (int i = 0; i < kTableNodes; ++i) {
        // theta is function 0.
        group.table_theta_only[static_cast<std::size_t>(s * kTableNodes + i)] =
            group.table[static_cast<std::size_t>((s * kTableNodes + i) * functions)];
      }
    }
    group.table_u_begin = u_begin;
    group.table_u_end = u_end;
    group.table_inv_width = 1.0 / width;
    group.table_segments = segments;
    // Measure, do not assume: compare what evaluate() publishes with the robust solver at 9 interior points of
    // every segment (none of them an interpolation node) plus both ends.
    achieved = 0.0;
    for (int s = 0; s < segments; ++s) {
      for (int j = 0; j <= 10; ++j) {
        const double u = u_begin + (s + j / 10.0) * width;
        const double p = u * u;
        exact(u, want.data());
        if (shape) {
          int segment = 0;
          double x = 0.0;
          if (!tableSegment(group, p, segment, x) ||
              !table_shape_writer_(parameters_, table_polynomials_, tableRow(group, segment), x, false, 1.0, 0.0,
                                   table_state)) {
            continue;  // at contact itself, or a theta a rounding below 0: evaluate() gives the rest shape there
          }
          achieved = std::max(achieved, std::fabs(table_state.half_angle_rad[0] - want[0]));
          for (int k = 0; k < 2 * n; ++k) {
            achieved = std::max(achieved, std::fabs(table_state.backbone_m.data()[4 + k] - want[1 + k]) / length_m);
          }
        } else {
          const ChamberGroupSolution got = solveGroup(group, p, false);
          achieved = std::max({achieved, std::fabs(got.half.rad - want[0]), std::fabs(got.half.cos - want[1]),
                               std::fabs(got.half.sin - want[2])});
        }
      }
    }
    if (achieved <= options_.table_tolerance_rad) break;
  }
  table_error_rad_ = std::max(table_error_rad_, achieved);
}

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

WallSolution FingerModel::solveRobust(const ChamberGroup& group, double gauge_pa, double atmospheric_pa) {
  return solveWall(gauge_pa, atmospheric_pa, group.shear_modulus_pa, group.chamber_height_m, group.chamber_gap_m,
                   group.wall_critical_height_m);
}

// The robust chain's usual path (solveWall's, simd_math.hpp) inline, its numbers in registers from the pressure to
// the caller: the same operations as solveWall, so the same bits, and finite by construction (s <= 1/20, D <= 1e6).
// false where solveWall's other paths must answer. theta, cos, sin, tan stay as set where the walls are apart.
__attribute__((always_inline)) inline bool FingerModel::usualWall(const ChamberGroup& group, double gauge_pa,
                                                                  double atmospheric_pa, double& stretch_excess,
                                                                  double& bulge_m, HalfAngle& half) {
  const double two_over_b = 2.0 / group.wall_critical_height_m;
  double m = 0.0;
  return wallStagesBySeries(gauge_pa, atmospheric_pa, group.shear_modulus_pa, group.chamber_height_m,
                            group.chamber_gap_m, two_over_b, stretch_excess, bulge_m, m) &&
         (!(bulge_m > group.chamber_gap_m) || usualWallHalfAngle(bulge_m, group.chamber_gap_m, two_over_b, m, half.rad,
                                                                 half.cos, half.sin, half.tan, half.iterations));
}

// The same coefficients as the row's theta, in the same order of operations: the same bits as evaluate().
inline double FingerModel::tableTheta(const ChamberGroup& group, int segment, double x) {
  return tableFunction(&group.table_theta_only[static_cast<std::size_t>(segment) * kTableNodes], 1, 0, x);
}

// solveGroup's theta alone, in registers (tipAngleAt, jointAnglesAt): the usual paths inline, the rest by solveRobust
// (the paper solver by solveGroup).
__attribute__((always_inline)) inline double FingerModel::halfAngleOf(const ChamberGroup& group,
                                                                      double gauge_pa) const {
  if (options_.solver == SolverKind::kTable) {
    int segment = 0;
    double x = 0.0;
    if (tableSegment(group, gauge_pa, segment, x)) {
      const double theta = tableTheta(group, segment, x);
      return theta > 0.0 ? theta : 0.0;  // a rounding error below 0 next to contact: 0 by definition
    }
    if (!(gauge_pa > group.contact_gauge_pa)) return 0.0;  // walls apart (or NaN, as solveGroup)
  }
  if (options_.solver == SolverKind::kPaper) return solveGroup(group, gauge_pa, false).half.rad;
  // Robust, and the table above its range: as solveGroup takes them, without its other outputs.
  double delta = 0.0, bulge_m = 0.0;
  HalfAngle half;
  if (usualWall(group, gauge_pa, parameters_.atmospheric_pressure_pa, delta, bulge_m, half)) return half.rad;
  return solveRobust(group, gauge_pa, parameters_.atmospheric_pressure_pa).half.rad;
}

ChamberGroupSolution FingerModel::solveGroup(const ChamberGroup& group, double gauge_pa, bool detail) const {
  ChamberGroupSolution r{1.0, 0.0, HalfAngle{}};
  const double p_o = parameters_.atmospheric_pressure_pa;
  switch (options_.solver) {
    case SolverKind::kRobust: {
      double delta = 0.0;
      if (usualWall(group, gauge_pa, p_o, delta, r.bulge_m, r.half)) {
        r.stretch = 1.0 + delta;
        return r;
      }
      const WallSolution w = solveRobust(group, gauge_pa, p_o);
      return {1.0 + w.stretch_excess, w.bulge_m, w.half};
    }
    case SolverKind::kPaper: {
      r.stretch = paper::stretch(energyGroup(gauge_pa, p_o, group.shear_modulus_pa));
      r.bulge_m = paper::bulge(r.stretch, group.chamber_height_m);
      const double theta = paper::halfAngle(r.bulge_m, group.chamber_gap_m, group.wall_critical_height_m);
      r.half.rad = theta;
      r.half.cos = std::cos(theta);
      r.half.sin = std::sin(theta);
      r.half.tan = r.half.sin / r.half.cos;
      return r;
    }
    case SolverKind::kTable: {
      int segment = 0;
      double x = 0.0;
      const bool in_table = tableSegment(group, gauge_pa, segment, x);
      // Above the table the robust chain answers, and it also gives the detail.
      if (!in_table && gauge_pa > group.contact_gauge_pa) {
        const WallSolution w = solveRobust(group, gauge_pa, p_o);
        return {1.0 + w.stretch_excess, w.bulge_m, w.half};
      }
      if (detail) {
        const double delta = stretchExcess(energyGroup(gauge_pa, p_o, group.shear_modulus_pa));
        r.stretch = 1.0 + delta;
        r.bulge_m = bulge(delta, group.chamber_height_m);
      }
      if (!in_table) return r;  // walls apart: theta = 0 exactly
      const auto k = static_cast<std::size_t>(segment);
      const double theta = tableTheta(group, segment, x);
      // Near contact the interpolant may dip a rounding error below 0: theta is 0 there by definition.
      if (!(theta > 0.0)) return r;
      r.half.rad = theta;
      // tan is not tabulated: jointsAndBackbone does not read it, and a shape table's shape comes from the table.
      r.half.tan = std::numeric_limits<double>::quiet_NaN();
      if (group.table_functions == kTableTrigFunctions) {
        const double* row = &group.table[k * kTableTrigFunctions * kTableNodes];
        r.half.cos = tableFunction(row, kTableTrigFunctions, 1, x);
        r.half.sin = tableFunction(row, kTableTrigFunctions, 2, x);
      } else {
        // A shape table has no cos and sin: writeState takes the shape from it directly, and the callers that come
        // here (tipAngleAt, jointAnglesAt) read theta only. NaN, so that nothing can use them unnoticed.
        r.half.cos = r.half.sin = std::numeric_limits<double>::quiet_NaN();
      }
      return r;
    }
  }
  return r;
}

FingerState restState(const FingerParameters& parameters) {
  const int n = parameters.chamber_count;
  FingerState s;
  s.stretch = Eigen::VectorXd::Ones(n);
  s.bulge_m = Eigen::VectorXd::Zero(n);
  s.half_angle_rad = Eigen::VectorXd::Zero(n);
  s.joint_angle_rad = Eigen::VectorXd::Zero(n);
  s.backbone_m = Eigen::Matrix2Xd::Zero(2, n + 2);
  const std::vector<HalfAngle> straight(static_cast<std::size_t>(n));
  jointsAndBackbone(parameters, straight.data(), s);
  return s;
}

void jointsAndBackbone(const FingerParameters& parameters, const HalfAngle* half, FingerState& out) {
  const int n = parameters.chamber_count;
  // theta_0: the passive base segment's face turns by a share of chamber 1's half angle (0 for an inert face).
  double theta_prev = 0.0, cos_prev = 1.0, sin_prev = 0.0;
  if (n > 0 && parameters.base_wall_share != 0.0) {
    theta_prev = parameters.base_wall_share * half[0].rad;
    sinCosSmall(theta_prev, cos_prev, sin_prev);
  }
  double dir_c = 1.0, dir_s = 0.0, tip_angle = 0.0;
  double x = parameters.base_segment_length_m, y = 0.0;
  bool contact = false;
  out.backbone_m(0, 0) = 0.0;
  out.backbone_m(1, 0) = 0.0;
  out.backbone_m(0, 1) = x;
  out.backbone_m(1, 1) = y;
  for (int i = 0; i < n; ++i) {
    const HalfAngle& h = half[i];
    out.half_angle_rad[i] = h.rad;
    contact = contact || h.rad > 0.0;
    const double q = theta_prev + h.rad;  // eq 37: q_n = theta_{n-1} + theta_n
    out.joint_angle_rad[i] = q;
    tip_angle += q;
    // (cos, sin)(q) = (cos, sin)(theta_{n-1}) * (cos, sin)(theta_n); Theta_n = Theta_{n-1} + q.
    const double rot_c = cos_prev * h.cos - sin_prev * h.sin;
    const double rot_s = sin_prev * h.cos + cos_prev * h.sin;
    const double c_new = dir_c * rot_c - dir_s * rot_s;
    dir_s = dir_s * rot_c + dir_c * rot_s;
    dir_c = c_new;
    const double z = parameters.segment_length_m[static_cast<std::size_t>(i)];  // eq 38
    x += z * dir_c;
    y += z * dir_s;
    out.backbone_m(0, i + 2) = x;
    out.backbone_m(1, i + 2) = y;
    theta_prev = h.rad;
    cos_prev = h.cos;
    sin_prev = h.sin;
  }
  out.tip_angle_rad = tip_angle;
  out.walls_in_contact = contact;
}

FingerState FingerModel::initialState() const {
  FingerState s = restState(parameters_);
  if (!options_.chamber_detail) {
    s.stretch.setConstant(std::numeric_limits<double>::quiet_NaN());
    s.bulge_m.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  return s;
}

inline bool FingerModel::writeTableShape(double gauge_pa, FingerState& out) const {
  const ChamberGroup& group = groups_[0];
  int segment = 0;
  double x = 0.0;
  if (!tableSegment(group, gauge_pa, segment, x)) return false;
  // The table holds the shape: only the detail, when asked for, still runs stages 1-3 (their series).
  double stretch = 1.0, bulge_m = 0.0;
  const bool detail = options_.chamber_detail;
  if (detail) {
    const double delta =
        stretchExcess(energyGroup(gauge_pa, parameters_.atmospheric_pressure_pa, group.shear_modulus_pa));
    stretch = 1.0 + delta;
    bulge_m = bulge(delta, group.chamber_height_m);
  }
  if (!table_shape_writer_(parameters_, table_polynomials_, tableRow(group, segment), x, detail, stretch, bulge_m,
                           out)) {
    return false;  // theta a rounding error below 0 next to contact: solveGroup gives theta = 0, the rest shape
  }
  out.gauge_pa = gauge_pa;
  return true;
}

// The table's shape first, inline in evaluate(); the other paths in a function of their own (noinline), whose prologue
// and register saves the table path would otherwise pay on every call.
inline bool FingerModel::writeState(double gauge_pa, FingerWorkspace& workspace, FingerState& out) const {
  if (table_shape_writer_ && writeTableShape(gauge_pa, out)) return true;
  return writeSolvedState(gauge_pa, workspace, out);
}

__attribute__((noinline)) bool FingerModel::writeSolvedState(double gauge_pa, FingerWorkspace& workspace,
                                                             FingerState& out) const {
  const bool detail = options_.chamber_detail;
  auto finite = [](const ChamberGroupSolution& r) {
    return std::isfinite(r.stretch) && std::isfinite(r.bulge_m) && std::isfinite(r.half.rad) &&
           std::isfinite(r.half.cos) && std::isfinite(r.half.sin);
  };
  // Every group is solved and checked before anything is written, so a failure leaves the previous state whole.
  if (groups_.size() == 1) {
    const ChamberGroup& group = groups_[0];
    const UniformWriter writer = uniformWriterFor(parameters_.chamber_count);
    if (options_.solver == SolverKind::kRobust) {
      double delta = 0.0, bulge_m = 0.0;
      HalfAngle half;
      if (usualWall(group, gauge_pa, parameters_.atmospheric_pressure_pa, delta, bulge_m, half)) {
        writer(parameters_, first_joint_series_, detail, 1.0 + delta, bulge_m, half.rad, half.cos, half.sin, half.tan,
               out);
        out.gauge_pa = gauge_pa;
        return true;
      }
    }
    // The rest (the robust solver's rare paths straight to solveRobust, not through solveGroup's usualWall again).
    ChamberGroupSolution r;
    if (options_.solver == SolverKind::kRobust) {
      const WallSolution w = solveRobust(group, gauge_pa, parameters_.atmospheric_pressure_pa);
      r = {1.0 + w.stretch_excess, w.bulge_m, w.half};
    } else {
      r = solveGroup(group, gauge_pa, detail);
    }
    if (!finite(r)) return false;
    writer(parameters_, first_joint_series_, detail, r.stretch, r.bulge_m, r.half.rad, r.half.cos, r.half.sin,
           r.half.tan, out);
    out.gauge_pa = gauge_pa;
    return true;
  }
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    workspace.group_solutions_[g] = solveGroup(groups_[g], gauge_pa, detail);
    if (!finite(workspace.group_solutions_[g])) return false;
  }
  for (std::size_t k = 0; k < group_of_chamber_.size(); ++k) {
    const ChamberGroupSolution& r = workspace.group_solutions_[static_cast<std::size_t>(group_of_chamber_[k])];
    const auto i = static_cast<Eigen::Index>(k);
    if (detail) {
      out.stretch[i] = r.stretch;
      out.bulge_m[i] = r.bulge_m;
    }
    workspace.chamber_half_[k] = r.half;
  }
  jointsAndBackbone(parameters_, workspace.chamber_half_.data(), out);
  out.gauge_pa = gauge_pa;
  return true;
}

const FingerState& FingerModel::evaluate(double gauge_pa, FingerWorkspace& ws) const {
  if (__builtin_expect(ws.shape_ != shape_, 0)) refuseWorkspace(ws);
  FingerState& state = ws.state_;
  if (!std::isfinite(gauge_pa)) {
    state.status = EvaluationStatus::kNotFinite;
    ws.has_last_ = false;  // the next finite pressure recomputes and resets the status
    return state;
  }
  if (ws.has_last_ && gauge_pa == ws.last_gauge_pa_) return state;  // unchanged pressure: nothing to do
  const bool vacuum = gauge_pa < 0.0;
  ++ws.computations_;
  if (!writeState(vacuum ? 0.0 : gauge_pa, ws, state)) {
    state.status = EvaluationStatus::kSolverFailure;
    ws.has_last_ = false;
    return state;
  }
  state.gauge_pa = gauge_pa;
  state.status = vacuum ? EvaluationStatus::kVacuum : EvaluationStatus::kOk;
  ws.has_last_ = true;
  ws.last_gauge_pa_ = gauge_pa;
  return state;
}

bool FingerModel::jointAnglesAt(double gauge_pa, double* q, double* half_angle_rad) const {
  std::array<double, kMaxChamberCount> theta;
  for (std::size_t g = 0; g < groups_.size(); ++g) theta[g] = halfAngleOf(groups_[g], gauge_pa);
  // eq 37: q_n = theta_{n-1} + theta_n; theta_0 = s0 theta_1, the passive base segment's face.
  double previous = parameters_.base_wall_share * theta[static_cast<std::size_t>(group_of_chamber_[0])];
  for (std::size_t k = 0; k < group_of_chamber_.size(); ++k) {
    const double t = theta[static_cast<std::size_t>(group_of_chamber_[k])];
    if (!std::isfinite(t)) return false;
    q[k] = previous + t;
    if (half_angle_rad) half_angle_rad[k] = t;
    previous = t;
  }
  return true;
}

double FingerModel::tipAngleAt(double gauge_pa) const {
  // Theta_N = sum_n q_n = theta_0 + 2 sum_n theta_n - theta_N. The half angles live on the stack (at most the largest
  // chamber_count), not in the model's scratch, so that const methods are safe to call from several threads.
  std::array<double, kMaxChamberCount> theta;
  for (std::size_t g = 0; g < groups_.size(); ++g) theta[g] = halfAngleOf(groups_[g], gauge_pa);
  double sum = 0.0, last = 0.0;
  for (std::size_t k = 0; k < group_of_chamber_.size(); ++k) {
    last = theta[static_cast<std::size_t>(group_of_chamber_[k])];
    sum += last;
  }
  return parameters_.base_wall_share * theta[static_cast<std::size_t>(group_of_chamber_[0])] + (2.0 * sum - last);
}

bool FingerModel::gaugeForTipAngle(double tip_angle_rad, double max_gauge_pa, double& gauge_pa,
                                   std::string& message) const {
  std::ostringstream why;
  if (!std::isfinite(tip_angle_rad) || tip_angle_rad < 0.0) {
    why << "tip angle " << formatExact(tip_angle_rad) << " rad is not a finite angle >= 0 (flexion is positive)";
    message = why.str();
    return false;
  }
  const int n = parameters_.chamber_count;
  // Every half angle stays below pi/2, so Theta_N < (2N - 1 + s0) pi/2.
  const double turns = 2 * n - 1 + parameters_.base_wall_share;
  const double limit = turns * kPi / 2;
  if (tip_angle_rad >= limit) {
    why << "tip angle " << formatExact(tip_angle_rad) << " rad is beyond the model's limit (2N-1+s0) pi/2 = "
        << formatExact(limit) << " rad, which no finite pressure reaches";
    message = why.str();
    return false;
  }
  if (tip_angle_rad == 0.0) {
    gauge_pa = 0.0;
    return true;
  }
  double answer;
  if (groups_.size() == 1) {
    // Identical chambers: Theta_N = (2N - 1 + s0) theta, and every stage inverts in closed form.
    if (!gaugeForHalfAngle(tip_angle_rad / turns, answer)) answer = std::numeric_limits<double>::infinity();
  } else {
    // Unequal chambers: Theta_N(P) is non-decreasing, so bisect on [0, max].
    if (tipAngleAt(max_gauge_pa) < tip_angle_rad) {
      answer = std::numeric_limits<double>::infinity();
    } else {
      double lo = 0.0, hi = max_gauge_pa;
      for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (tipAngleAt(mid) < tip_angle_rad ? lo : hi) = mid;
      }
      answer = hi;
    }
  }
  if (!(answer <= max_gauge_pa)) {
    why << "tip angle " << formatExact(tip_angle_rad) << " rad needs more than the allowed " << formatExact(max_gauge_pa)
        << " Pa gauge";
    if (std::isfinite(answer)) why << " (" << formatExact(answer) << " Pa)";
    message = why.str();
    return false;
  }
  gauge_pa = answer;
  return true;
}

bool FingerModel::gaugeForHalfAngle(double half_angle_rad, double& gauge_pa) const {
  if (groups_.size() != 1 || !(half_angle_rad > 0) || !(half_angle_rad < kPi / 2)) return false;
  const ChamberGroup& g = groups_[0];
  const double h = bulgeForHalfAngle(half_angle_rad, g.chamber_gap_m, g.wall_critical_height_m);
  const double p = gaugeForBulge(h, g.chamber_height_m, g.shear_modulus_pa, parameters_.atmospheric_pressure_pa);
  if (!std::isfinite(p)) return false;
  gauge_pa = p;
  return true;
}

BatchBuffers::BatchBuffers(std::size_t count, int chamber_count) {
  const auto n = static_cast<std::size_t>(chamber_count);
  for (auto* v : {&stretch, &bulge_m, &half_angle_rad, &joint_angle_rad}) v->resize(count * n);
  backbone_m.resize(count * 2 * (n + 2));
  tip_angle_rad.resize(count);
  status.resize(count);
}

BatchOutputs BatchBuffers::outputs() {
  BatchOutputs o;
  o.stretch = stretch.data();
  o.bulge_m = bulge_m.data();
  o.half_angle_rad = half_angle_rad.data();
  o.joint_angle_rad = joint_angle_rad.data();
  o.backbone_m = backbone_m.data();
  o.tip_angle_rad = tip_angle_rad.data();
  o.status = status.data();
  return o;
}

const char* batchPathName(BatchPath path) {
  switch (path) {
    case BatchPath::kBest: return "best";
    case BatchPath::kScalar: return "scalar";
    case BatchPath::kGeneric: return "generic";
    case BatchPath::kAvx2: return "avx2";
    case BatchPath::kAvx512: return "avx512";
  }
  return "best";
}

bool batchPathAvailable(BatchPath path) {
  switch (path) {
    case BatchPath::kBest:
    case BatchPath::kScalar:
    case BatchPath::kGeneric:
      return true;
#if defined(__x86_64__)
    case BatchPath::kAvx2: return __builtin_cpu_supports("avx2");
    case BatchPath::kAvx512: return __builtin_cpu_supports("avx512f");
#else
    case BatchPath::kAvx2:
    case BatchPath::kAvx512:
      return false;
#endif
  }
  return false;
}

namespace {

static_assert(kMaxChamberCount <= 64, "the batch kernel keeps at most 64 directions per lane");

using BatchKernel = void (*)(const UniformRobustSpec&, const double*, std::size_t, const BatchOutputs&);

BatchKernel batchKernel(BatchPath path) {
#if defined(__x86_64__)
  if (path == BatchPath::kBest) {
    path = batchPathAvailable(BatchPath::kAvx512) ? BatchPath::kAvx512
           : batchPathAvailable(BatchPath::kAvx2) ? BatchPath::kAvx2
                                                  : BatchPath::kGeneric;
  }
  if (path == BatchPath::kAvx512 && batchPathAvailable(path)) return batchUniformRobustAvx512;
  if (path == BatchPath::kAvx2 && batchPathAvailable(path)) return batchUniformRobustAvx2;
#endif
  if (path == BatchPath::kBest || path == BatchPath::kGeneric) return batchUniformRobustGeneric;
  return nullptr;
}

}  // namespace

void FingerModel::evaluateMany(const double* gauge_pa, std::size_t count, const BatchOutputs& out,
                               FingerWorkspace& workspace, BatchPath path) const {
  if (path != BatchPath::kScalar && !batchPathAvailable(path)) {
    throw std::invalid_argument(std::string("evaluateMany: the batch path '") + batchPathName(path) +
                                "' is not available on this CPU or build");
  }
  const auto n = static_cast<std::size_t>(parameters_.chamber_count);
  if (path != BatchPath::kScalar && options_.solver == SolverKind::kRobust && groups_.size() == 1) {
    const ChamberGroup& g = groups_[0];
    const UniformRobustSpec spec{parameters_.chamber_count, parameters_.atmospheric_pressure_pa, g.shear_modulus_pa,
                                 g.chamber_height_m, g.chamber_gap_m, g.wall_critical_height_m,
                                 parameters_.base_segment_length_m, parameters_.segment_length_m.data(),
                                 parameters_.base_wall_share, first_joint_series_};
    batchKernel(path)(spec, gauge_pa, count, out);
    return;
  }
  if (workspace.shape_ != shape_) refuseWorkspace(workspace);
  FingerState& state = workspace.batch_state_;
  if (state.stretch.size() == 0) state = initialState();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto row = [n, nan](const Eigen::VectorXd& from, double* to, std::size_t i, bool answered) {
    if (!to) return;
    if (answered) std::copy(from.data(), from.data() + n, to + i * n);
    else std::fill(to + i * n, to + (i + 1) * n, nan);
  };
  for (std::size_t i = 0; i < count; ++i) {
    const double p = gauge_pa[i];
    EvaluationStatus status = !std::isfinite(p) ? EvaluationStatus::kNotFinite
                              : p < 0.0         ? EvaluationStatus::kVacuum
                                                : EvaluationStatus::kOk;
    if (status != EvaluationStatus::kNotFinite && !writeState(p < 0.0 ? 0.0 : p, workspace, state)) {
      status = EvaluationStatus::kSolverFailure;
    }
    const bool answered = status == EvaluationStatus::kOk || status == EvaluationStatus::kVacuum;
    const FingerState& s = state;
    row(s.stretch, out.stretch, i, answered);
    row(s.bulge_m, out.bulge_m, i, answered);
    row(s.half_angle_rad, out.half_angle_rad, i, answered);
    row(s.joint_angle_rad, out.joint_angle_rad, i, answered);
    if (out.backbone_m) {
      double* o = out.backbone_m + i * 2 * (n + 2);
      if (answered) std::copy(s.backbone_m.data(), s.backbone_m.data() + 2 * (n + 2), o);
      else std::fill(o, o + 2 * (n + 2), nan);
    }
    if (out.tip_angle_rad) out.tip_angle_rad[i] = answered ? s.tip_angle_rad : nan;
    if (out.status) out.status[i] = static_cast<int>(status);
  }
}

}  // namespace pneumatic_finger
