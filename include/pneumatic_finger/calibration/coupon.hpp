// The elastomer from a coupon test (docs/CALIBRATE.md, "The elastomer from a coupon test"): a uniaxial tensile test's
// engineering strain and nominal stress, checked, and the wall law's material keys fitted to it (Ceres), with their
// uncertainty. ROS-free; the calibration room's, so the rest of the core never sees the solver.
#pragma once

#include <string>
#include <vector>

#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/pressure_range.hpp"

namespace pneumatic_finger {

/// One row of a uniaxial tensile test: engineering strain (-, the stretch less 1) and nominal stress (Pa, the force
/// over the coupon's undeformed section).
struct CouponRow {
  double engineering_strain = 0.0;
  double nominal_stress_pa = 0.0;
  int line = 0;  ///< its line in the file, for messages (0: from columns)
};

/// A coupon test, checked (checkCouponRows): at least four rows, strain rising from >= 0, a stress that does not fall.
struct CouponTest {
  std::vector<CouponRow> rows;
  std::string origin;  ///< the file or "data", for messages
};

/// Reads a CSV: '#' comments, a header with engineering_strain and nominal_stress_pa (other columns ignored), one row
/// per line. @throws ParameterError naming the file, the row and what was expected (checkCouponRows' rules too).
CouponTest loadCouponCsv(const std::string& path);

/// The rows as given (Python's columns), checked. @throws ParameterError as loadCouponCsv.
CouponTest couponFromColumns(const std::vector<double>& engineering_strain, const std::vector<double>& nominal_stress_pa,
                             const std::string& origin);

/// The checks every coupon gets, with the reason named: finite numbers; a strain that starts at 0 or above and rises
/// row by row; a strain in ratio, not percent (none above 20, 2000 %); a stress in Pa, not kPa or MPa (the secant
/// modulus at the last row at least 1 kPa: softer than any elastomer a finger is cast in otherwise); a stress that does
/// not fall by more than 2 % of its largest so far (past rupture, or an unloading curve). @throws ParameterError.
void checkCouponRows(const std::vector<CouponRow>& rows, const std::string& origin);

/// The wall law's material, fitted to a coupon: the shear modulus mu and Gent's locking invariant J_m (0 for a
/// Neo-Hookean fit), and the coupon's preload: the test's zero taken with the coupon already stretched by
/// preload_strain (its first row's stress is not 0), so that the stretch is (1 + preload)(1 + strain).
struct CouponFit {
  bool gent = true;
  double shear_modulus_pa = 0.0, wall_locking_jm = 0.0, preload_strain = 0.0;
  /// One standard deviation of each (the covariance at the optimum, scaled by the residuals' variance); 0 for a key
  /// not fitted.
  double shear_modulus_sd_pa = 0.0, wall_locking_jm_sd = 0.0, preload_strain_sd = 0.0;
  double rms_relative_error = 0.0, max_relative_error = 0.0;  ///< |model - measured| / measured over the rows
  std::vector<double> model_stress_pa;                          ///< the fit's stress at each row (Pa)
  int starts = 0;                                               ///< the multi-start's starting points
};

/// Nominal stress (Pa) of an incompressible Gent solid (@p locking_jm > 0; 0: Neo-Hookean) pulled to stretch
/// @p stretch: mu (lambda - lambda^-2) / (1 - (I1 - 3) / J_m), I1 = lambda^2 + 2 / lambda. NaN at or past the lock.
double uniaxialNominalStressPa(double stretch, double shear_modulus_pa, double locking_jm);

/// The elastomer's law by name: true for "gent", false for "neo-hookean". @throws ParameterError for another name.
bool parseCouponLaw(const std::string& name);

/// Fits mu, J_m (when @p gent) and the preload to @p test by least squares on the relative stress error (a small
/// strain weighs as much as a large one), from a multi-start over the locking and the preload; Ceres Solver.
/// @throws ParameterError when no start converges.
CouponFit fitCoupon(const CouponTest& test, bool gent = true);

/// The fit in words, for a report or a parameter file's comment: each key with its standard deviation, the preload,
/// the errors, the rows. Every line starts with "# ".
std::string couponFitReport(const CouponFit& fit, const CouponTest& test);

/// The parameter file --coupon --output writes: @p base (a parameter file's keys) with shear_modulus_pa and
/// wall_locking_jm replaced by @p fit's, then @p range's keys; the caller adds the report as comments.
/// @throws ParameterError for the paper law, whose shear_modulus_pa is an effective stiffness, not the elastomer's.
std::string couponParameterYaml(RawParameterMap base, const CouponFit& fit, const PressureRange& range);

}  // namespace pneumatic_finger
