// The six stages of docs/MODEL.md ("The chain") as separate, testable functions.
//
// Two families:
//  - the robust forms (namespace-level functions): cancellation-free, finite for every finite input, no
//    allocation; accurate to a few ulp (test/test_stages.cpp and test/test_hard_cases.cpp against a quad reference).
//  - the paper's closed forms (namespace `paper`): eq 10-12 (trigonometric Cardano) and eq 16-35 (Ferrari),
//    written as printed, with the one correction docs/MODEL.md allows: a quartic root counts only if it satisfies
//    Wang's relation.
#pragma once

#include <array>

namespace pneumatic_finger {

/// Largest energy group the chain is evaluated at. Beyond it theta is pi/2 to double precision
/// (tan(theta) > 1e90), so clamping there changes no output digit and keeps every later stage finite.
constexpr double kMaxEnergyGroup = 1e200;

/// Stage 1 (eq 2-3, docs/MODEL.md): the dimensionless energy group g = 2 Psi / mu = P (2 P_o + P) / (P_o mu).
/// @param[in] gauge_pa gauge pressure P >= 0 (Pa); negative values are treated as 0 (vacuum is outside the model)
/// @param[in] atmospheric_pa P_o (Pa), > 0
/// @param[in] shear_modulus_pa mu (Pa), > 0
/// @return g in [0, kMaxEnergyGroup]; written as a product so that small P loses no digits
double energyGroup(double gauge_pa, double atmospheric_pa, double shear_modulus_pa);

/// Stage 2 (eq 5-12): the stretch excess delta = lambda - 1 of the largest root of
/// lambda^3 - (g + 3) lambda + 2 = 0, solved in delta itself (delta^2 (3 + delta) = g (1 + delta)), so that no
/// digits are lost where delta ~ sqrt(g/3) -> 0: Halley steps from a rational first guess that is within 0.43 %
/// for every g; for g > 1e30, where the polynomial's products would overflow, Newton on the equivalent fixed
/// point delta = sqrt(g (1 + delta)/(3 + delta)).
/// @param[in] g energy group, >= 0
/// @return delta >= 0 (0 exactly at g = 0)
double stretchExcess(double g);

/// Stage 3 (eq 13-14, docs/MODEL.md form): wall bulge h = (L/2)(sqrt(2 lambda^2 - 1) - 1), evaluated from delta in the
/// factored form L delta (2 + delta) / (sqrt(1 + 4 delta + 2 delta^2) + 1), which is exact near rest.
/// @param[in] stretch_excess delta = lambda - 1 >= 0
/// @param[in] chamber_height_m L (m)
/// @return h (m), 0 at rest
double bulge(double stretch_excess, double chamber_height_m);

/// The half angle theta of one wall with its cosine and sine (the backbone needs them; computing them here
/// from tan(theta) avoids two trigonometric calls per chamber).
struct HalfAngle {
  double rad = 0.0;  ///< theta in [0, pi/2]
  double cos = 1.0;  ///< cos(theta)
  double sin = 0.0;  ///< sin(theta)
  double tan = 0.0;  ///< tan(theta) (+inf at pi/2): the solve's own variable, from which joint 1's direction is a series
  int iterations = 0;  ///< solver steps used (0 below contact); for tests and benchmarks
};

/// Stage 4 (eq 15, J. Wang): the half angle theta whose bulge h(theta) = b/(2 cos) (sin + c/b + sqrt(2c/b sin +
/// c^2/b^2)) equals @p bulge_m; 0 while h <= c (the walls do not touch yet).
/// Eq 15 is equivalent to tan(theta) = H - sqrt(2kH) (1 + tan^2)^(1/4) with H = 2h/b, k = c/b (substitute
/// v = c/b + sqrt(2c/b sin + c^2/b^2)). With w = (1 + tan^2)^(1/4) that is a polynomial in w - 1, increasing on
/// its bracket, solved by safeguarded Halley steps; theta = atan(tan theta) stays well conditioned up to pi/2, where
/// asin(sin theta) does not. Very large bulges use Newton in tan(theta) with overflow-free forms.
/// @param[in] bulge_m h (m), >= 0
/// @param[in] gap_m c (m), >= 0
/// @param[in] wall_critical_height_m b (m), > 0
HalfAngle halfAngle(double bulge_m, double gap_m, double wall_critical_height_m);

/// Joint 1's direction for identical chambers (docs/MODEL.md stage 5), e^(i q_1) = e^(i a theta) with a = 1 + s0, as
/// power series in t = tan(theta): cos(a atan t) = sum cos_c[k] t^2k and sin(a atan t) = t sum sin_c[k] t^2k. They are
/// Re and Im of ((1 + i t)/(1 - i t))^(a/2) = sum i^n b_n t^n, and (1 + t^2) f' = i a f gives b_0 = 1, b_1 = a and
/// (n + 1) b_(n+1) = a b_n + (n - 1) b_(n-1): positive terms, so the coefficients come out to a few ulp. For t <= 1/8 and
/// a <= 2, b_n t^n <= (n + 1) 8^-n: the first terms left out (n = 20, 21) are below 2e-17 relative. The backbone takes
/// the direction from t beside the arctangent rather than after it (joint_chain.hpp, firstJoint).
struct FirstJointSeries {
  double cos_c[10];  ///< (-1)^k b_2k
  double sin_c[10];  ///< (-1)^k b_(2k+1)
};

/// The series above for the base face's share @p base_wall_share (s0, in [0, 1]).
FirstJointSeries firstJointSeries(double base_wall_share);

/// One chamber's wall at one pressure: what stages 1-4 give.
struct WallSolution {
  double stretch_excess = 0.0;  ///< delta = lambda - 1 (-)
  double bulge_m = 0.0;         ///< h (m)
  HalfAngle half;               ///< theta, with its cosine and sine
};

/// Stages 1-4 chained with the robust forms: gauge pressure -> delta, h -> theta. Where s = sqrt(g/3) <= 1/20 (the
/// validated range and beyond), delta, h and stage 4's m come from power series in s (docs/MODEL.md stages 2-4);
/// otherwise g -> delta -> h -> theta by the functions above. The model's robust solver and its table builder call it;
/// the batch kernel shares its arithmetic (src/core/wall_chain.hpp) and takes the same branch per pressure.
/// @param[in] gauge_pa P (Pa gauge); <= 0 gives the rest wall
/// @param[in] atmospheric_pa P_o (Pa)
/// @param[in] shear_modulus_pa mu (Pa)
/// @param[in] chamber_height_m L (m)
/// @param[in] gap_m c (m)
/// @param[in] wall_critical_height_m b (m)
WallSolution solveWall(double gauge_pa, double atmospheric_pa, double shear_modulus_pa, double chamber_height_m,
                       double gap_m, double wall_critical_height_m);

/// Wang's relation itself (eq 15), h(theta); used to accept quartic roots and by the calibration tool.
double bulgeForHalfAngle(double half_angle_rad, double gap_m, double wall_critical_height_m);

namespace paper {

/// Eq 10-12 as printed (angles in radians): T = sqrt(-1 - (-(g+3))^3/27), phi = pi + atan(T/-1),
/// lambda = 2 cbrt(sqrt(1 + T^2)) cos(phi/3). Returns lambda (not lambda - 1).
double stretch(double g);

/// docs/MODEL.md's bulge written directly, (L/2)(sqrt(2 lambda^2 - 1) - 1): the form a reader of eq 14 would write.
double bulge(double stretch, double chamber_height_m);

/// Coefficients A..E of eq 16-22 (quartic in y = sin theta).
std::array<double, 5> quarticCoefficients(double bulge_m, double gap_m, double wall_critical_height_m);

/// The intermediate terms of eq 23-33: depressed quartic x^4 + p x^2 + q x + r (eq 24-27), depressed resolvent
/// cubic beta^3 + p2 beta + q2 (eq 30) and its discriminant q2^2/4 + p2^3/27, whose sign picks eq 33's branch.
struct FerrariTerms {
  double p, q, r, p2, q2, discriminant;
};
FerrariTerms ferrariTerms(const std::array<double, 5>& quartic);

/// Eq 23-35: Ferrari on the quartic, then theta = asin(y) for the root that satisfies Wang's relation
/// (relative residual below 1e-6). Returns theta, 0 when h <= c, or NaN when no root passes: the paper's solver
/// has no answer there (the tests record where).
double halfAngle(double bulge_m, double gap_m, double wall_critical_height_m);

}  // namespace paper

}  // namespace pneumatic_finger
