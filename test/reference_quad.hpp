// The high-precision reference every solver is measured against.
//
// Independent of the library on purpose: it uses docs/MODEL.md's relations literally (the stretch polynomial, the
// square-root bulge, Wang's eq 15 itself, the backbone sums with explicit cos/sin), evaluated in __float128
// (113-bit mantissa, GCC's libquadmath), and solves each monotone relation by bisection to the last quad bit.
// None of the library's reformulations (delta fixed point with Newton, factored bulge, tan-form of eq 15, rotation recurrence) appear here.
#pragma once

#include <vector>

namespace reference {

struct ChamberGeometry {
  double chamber_height_m, wall_critical_height_m, chamber_gap_m, shear_modulus_pa;
};

/// One chamber's chain at one pressure, rounded to double at the end.
struct ChamberChain {
  double energy_group;
  double stretch_excess;  // lambda - 1, from the quad lambda
  double bulge_m;
  double half_angle_rad;
};

ChamberChain chamberChain(double gauge_pa, double atmospheric_pa, const ChamberGeometry& chamber);

/// Stage 4 alone: the half angle for a given bulge (eq 15 by bisection in quad).
double halfAngleForBulge(double bulge_m, double gap_m, double wall_critical_height_m);

struct Finger {
  std::vector<double> half_angle_rad;   // theta_n
  std::vector<double> joint_angle_rad;  // q_n
  std::vector<double> x_m, y_m;         // O_0..O_{N+1}
  double tip_angle_rad;
};

/// The whole finger (stages 1-6) in quad precision. @p base_wall_share: theta_0 = s0 theta_1 (joint 1).
Finger finger(double gauge_pa, double atmospheric_pa, const std::vector<ChamberGeometry>& chambers,
              const std::vector<double>& segment_length_m, double base_segment_length_m,
              double base_wall_share = 0.0);

}  // namespace reference
