// Stages 5-6 for a finger of identical chambers, written straight into a FingerState: from the half angle (the robust
// and paper solvers) or from the chamber table's polynomials (the table solver). One instance per chamber count up to
// kUnrolledChambers, picked at construction. Internal header of src/core (finger_model.cpp, chamber_table.cpp).
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <utility>

#include "pneumatic_finger/core/finger_model.hpp"
#include "chamber_table.hpp"
#include "joint_chain.hpp"

namespace pneumatic_finger {

namespace {  // NOLINT(build/namespaces): as simd_math.hpp, internal to each translation unit

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

// The shape from the half angle: firstJoint and uniformPoints (joint_chain.hpp) are shared with the batch kernel, so
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
inline Writer writerFor(int chamber_count) {
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
inline UniformWriter uniformWriterFor(int chamber_count) {
  return writerFor<UniformWriter, PickUniform>(chamber_count);
}

using TableShapeWriter = bool (*)(const FingerParameters&, TablePolynomials, const double*, double, bool, double,
                                  double, FingerState&);
template <int kChambers>
struct PickTableShape {
  static constexpr TableShapeWriter value = &tableShape<kChambers>;
};
inline TableShapeWriter tableShapeWriterFor(int chamber_count) {
  return writerFor<TableShapeWriter, PickTableShape>(chamber_count);
}

}  // namespace

}  // namespace pneumatic_finger
