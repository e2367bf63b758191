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

/// The membrane law (docs/MODEL.md "The membrane law") literally: P(lambda) = (4 mu t/L)(1/lambda - 1/lambda^7)
/// J_m/(J_m - (2 lambda^2 + lambda^-4 - 3)) (the Gent factor 1 for J_m = 0), in quad.
struct Membrane {
  double shear_modulus_pa, wall_thickness_m, chamber_height_m, locking_jm;
};

/// The pressure maximum's stretch excess (the first zero of dP/dlambda, by a scan and bisection of its literal
/// derivative), and the pressure there; +inf for a wall that locks first.
double membraneLimitStretchExcess(const Membrane& wall);
double membraneLimitGaugePa(const Membrane& wall);

/// The stretch excess on the rising branch at @p gauge_pa (below the limit), by bisection on P.
double membraneStretchExcess(const Membrane& wall, double gauge_pa);

/// The pressure at @p stretch_excess, the law evaluated in quad and rounded once.
double membraneGaugePa(const Membrane& wall, double stretch_excess);

}  // namespace reference
