// The membrane wall law (docs/MODEL.md, "The membrane law"): stages 1-3 for an inflated elastomer wall that balloons.
//
// A chamber's wall is taken as a thin spherical membrane of rest radius R = L/2 and rest thickness t, of an
// incompressible Neo-Hookean (or Gent) elastomer of shear modulus mu, stretched equally in every direction by
// lambda = 1 + delta. Laplace's law with the membrane's tension gives the gauge pressure explicitly:
//
//   P(lambda) = (4 mu t / L) (1/lambda - 1/lambda^7) J_m / (J_m - (I1 - 3)),   I1 - 3 = 2 lambda^2 + lambda^-4 - 3,
//
// (the Gent factor is 1 for J_m = 0, Neo-Hookean), and the wall's bulge is its radial growth, h = (L/2) delta.
// P rises from 0, and for a Neo-Hookean wall (and a Gent wall with a large J_m: test/test_membrane_wall.cpp has one at 50 and none at 6) reaches a maximum, the limit
// point, beyond which it falls: there a pressure does not determine the stretch. Below it the stretch is the root on
// the rising branch. Stage 4 (Wang's flexion) and the rest of the chain are the paper's.
#pragma once

#include <array>
#include <vector>

#include "pneumatic_finger/core/stages.hpp"

namespace pneumatic_finger {

/// One chamber group's membrane: its constants and its limit point, computed once (a model builds it).
struct MembraneWall {
  double chamber_height_m = 0.0;   ///< L (m): the rest radius is L/2
  double pressure_scale_pa = 0.0;  ///< 4 mu t / L (Pa); thick wall: mu
  /// The thick wall (wall_law: thick; docs/MODEL.md "The thick wall"): an incompressible sphere of inner radius
  /// A = L/2 and outer radius B = A + t, delta the inner surface's stretch excess. false: the thin membrane.
  bool thick = false;
  double inner_outer_volume_ratio = 1.0;  ///< (A/B)^3: lambda_b^3 - 1 = (A/B)^3 (lambda_a^3 - 1)
  double outer_inner_ratio = 1.0;         ///< B/A: the outer face's bulge is B (lambda_b - 1)
  /// The bulge that bends the finger is the outer face's (a thick wall with wall_flexion_face: outer); false: the
  /// inner face's, (L/2) delta (the thin membrane's one face, or a thick wall's chamber itself).
  bool outer_face_bends = false;
  /// Wang's bulge h per unit stretch excess of the face that bends the finger (m): kappa L/2 for the inner face,
  /// kappa B/A L/2 for the outer one's delta_b; kappa the share of the sphere's bulge that tilts the wall
  /// (wall_bulge_share, 1 as derived).
  double bulge_per_stretch_m = 0.0;
  /// Past the limit point |dP/ddelta| <= decay_scale_pa / lambda^2 (the supplied volume's snap search ends by it):
  /// 4 mu t/L for the membrane, 4 mu B/A for the thick wall.
  double decay_scale_pa = 0.0;
  double locking_jm = 0.0;         ///< J_m (-); 0: Neo-Hookean
  double locking_stretch_excess;   ///< delta where I1 - 3 = J_m (the wall locks; +inf for J_m = 0)
  /// The thick Gent wall's pressure in closed form (thick_wall.cpp): the roots of 2x^3 - (J_m + 3)x^2 + 1, where the
  /// Gent factor's denominator vanishes in x = lambda^2 (x_s in (0, 1), x_n < 0, and x_l, the lock's lambda^2),
  /// their square roots (of -x_n for x_n) and partial-fraction weights 1/prod_{j != i}(x_i - x_j).
  std::array<double, 3> gent_root_x{}, gent_root_sqrt{}, gent_weight{};
  double limit_stretch_excess;     ///< delta at the first pressure maximum (+inf: P rises to the lock)
  double limit_gauge_pa;           ///< P there (Pa; +inf without a maximum)
  /// The far branch (docs/MODEL.md, "The snap-through"): a Gent wall with a limit point stiffens again before its
  /// lock, so P falls from the limit to a minimum and rises again. The far branch is the rising part past that
  /// minimum, where a wall snaps to at the limit pressure and holds until the pressure falls to the minimum, its
  /// lower turning point. +inf for both when there is no far branch (Neo-Hookean: the wall balloons without bound).
  double far_turning_stretch_excess;  ///< delta at the pressure minimum past the limit point
  double far_turning_gauge_pa;        ///< P there (Pa): the far branch holds down to it, then snaps back
  /// Where the wall snaps under a rising pressure (docs/MODEL.md, "Where it snaps"): its limit point where it folds;
  /// else, a Gent wall that locks first, where the pressure per bulge of the bending face is least (the bend rises
  /// fastest); +inf for a wall that only stiffens from rest. NaN until setSnapPoint (a model built to say it).
  double snap_stretch_excess;  ///< delta there
  double snap_gauge_pa;        ///< P there (Pa)
  /// Where the rising branch's Newton steps start (membraneStretchExcess): P and dP/ddelta at kGuessNodes + 1
  /// stretches from rest to the limit point (or the lock), closer together towards both ends. Empty (has_guess
  /// false) where P rises without a limit or a lock.
  static constexpr int kGuessNodes = 32;
  bool has_guess = false;
  std::array<double, kGuessNodes + 1> guess_stretch_excess{}, guess_gauge_pa{}, guess_slope_pa{};
  /// The rising branch's inverse (docs/MODEL.md, "The wall's inverse"; src/core/wall_inverse.hpp): delta = q g(s) for
  /// P up to inverse_top_gauge_pa, q = P / inverse_top_gauge_pa and s = sqrt(1 - q), g a degree-15 polynomial on each of
  /// inverse_pieces equal pieces of s in [0, 1], checked against the law at build. 0 pieces: no inverse (the Newton
  /// steps from the starting table answer instead), as above the top of a wall that rises to its lock.
  static constexpr int kInverseCoefficients = 16;
  static constexpr int kInverseMaxPieces = 64;
  double inverse_top_gauge_pa = 0.0;  ///< the limit pressure, or where a wall without one stops the inverse (Pa)
  double inverse_scale_per_pa = 0.0;  ///< 1 / inverse_top_gauge_pa
  int inverse_pieces = 0;
  /// 1: delta; 2: delta and the outer face's delta_b = q g_b(s) (outer_face_bends, whose bulge would otherwise take a
  /// cube root per evaluation).
  int inverse_functions = 1;
  /// Per piece, from s = 0 (the top): kInverseCoefficients for g, x^0 first, then as many for g_b.
  std::vector<double> inverse_coefficients;
};

/// The membrane of a wall of height @p chamber_height_m (L), thickness @p wall_thickness_m (t), shear modulus
/// @p shear_modulus_pa (mu) and Gent locking invariant @p locking_jm (J_m, 0 for none), with its limit point.
/// @p thick: the thick wall; @p outer_face_bends: its outer face's bulge bends the finger, else its inner face's;
/// @p bulge_share: kappa, the share of that face's bulge that tilts the wall.
MembraneWall membraneWall(double shear_modulus_pa, double wall_thickness_m, double chamber_height_m,
                          double locking_jm, bool thick = false, bool outer_face_bends = true,
                          double bulge_share = 1.0);

/// Builds @p wall's inverse (MembraneWall::inverse_*, docs/MODEL.md "The wall's inverse") from its law and starting
/// table: 4 to 64 pieces, each checked against the law's Newton root at its Chebyshev extrema, the count doubling
/// until every piece holds. Tens to hundreds of microseconds, so a model builds it only when it will be evaluated
/// often (ModelOptions::wall_inverse). Leaves inverse_pieces 0 where no count holds (membraneStretchExcess then takes
/// Newton steps, as without it).
void buildRisingInverse(MembraneWall& wall);

/// Sets @p wall's snap point (MembraneWall::snap_*) from its law and limit point (src/core/wall_snap.cpp).
void setSnapPoint(MembraneWall& wall);

/// A thick wall's outer face's bulge kappa B (lambda_b - 1) (m) from its stretch excess @p outer_stretch_excess.
inline double outerFaceBulgeM(const MembraneWall& wall, double outer_stretch_excess) {
  return wall.bulge_per_stretch_m * outer_stretch_excess;
}

/// The bulge h (m) that bends the finger at stretch excess @p delta: kappa (L/2) delta for the membrane (and a thick
/// wall's inner face), kappa B (lambda_b - 1) for a thick wall's outer face.
double membraneBulgeM(const MembraneWall& wall, double delta);

/// The stretch excess at which the bulge that bends the finger is @p bulge_m (>= 0): membraneBulgeM inverted.
double membraneStretchForBulge(const MembraneWall& wall, double bulge_m);

/// The law itself: the gauge pressure (Pa) at stretch excess @p delta >= 0, without cancellation near rest
/// (1/lambda - 1/lambda^7 = (lambda^6 - 1)/lambda^7 with lambda^6 - 1 a polynomial in delta). +inf at or beyond the
/// locking stretch.
double membraneGaugeForStretchExcess(const MembraneWall& wall, double delta);

/// P (Pa) and dP/ddelta (Pa) at @p delta >= 0 together (Newton steps need both; they share most of their terms). +inf
/// for both at or beyond the lock.
void membraneGaugeAndSlope(const MembraneWall& wall, double delta, double& gauge_pa, double& slope_pa);

/// The stretch excess on the rising branch for @p gauge_pa in [0, limit_gauge_pa): the wall's inverse where it has
/// one (buildRisingInverse), else safeguarded Newton steps on P, bracketed by [0, limit_stretch_excess]. NaN for a pressure at or beyond the limit point, negative or NaN.
double membraneStretchExcess(const MembraneWall& wall, double gauge_pa);

/// The stretch excess on the far branch for @p gauge_pa in (far_turning_gauge_pa, +inf): the same safeguarded Newton
/// steps, bracketed by [far_turning_stretch_excess, locking_stretch_excess]. NaN where there is no far branch or the
/// pressure is at or below its turning point.
double membraneFarStretchExcess(const MembraneWall& wall, double gauge_pa);

/// Stages 1-4 under the membrane law: delta, h = (L/2) delta, then Wang's half angle (halfAngle). At or beyond the
/// limit point every field is NaN.
WallSolution solveMembraneWall(const MembraneWall& wall, double gauge_pa, double gap_m,
                               double wall_critical_height_m);

/// Stages 3-4 from a stretch excess @p delta (any branch): h = (L/2) delta, then Wang's half angle.
WallSolution membraneWallAtStretch(const MembraneWall& wall, double delta, double gap_m,
                                   double wall_critical_height_m);

/// The inverse: the gauge pressure (Pa) that gives bulge @p bulge_m, or NaN when that bulge lies beyond the limit
/// point (no pressure holds it).
double membraneGaugeForBulge(const MembraneWall& wall, double bulge_m);

}  // namespace pneumatic_finger
