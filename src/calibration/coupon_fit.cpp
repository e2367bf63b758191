// The wall law's material fitted to a coupon test with Ceres Solver (coupon.hpp): bounded least squares on the
// relative stress error, a multi-start over the locking and the preload so that the fit stays global, and the
// covariance at the optimum for the uncertainty.
#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "pneumatic_finger/calibration/coupon.hpp"
#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pneumatic_finger {

namespace {

// One row's relative error, (model - measured) / measured. The locking enters as its inverse, alpha = 1 / J_m, so
// that the Neo-Hookean solid is alpha = 0, inside the bounds; a step that reaches the lock is refused (false), and
// the trust region shrinks.
struct RelativeStressError {
  double strain, stress_pa, scale_pa;
  template <class T>
  bool operator()(const T* mu, const T* alpha, const T* preload, T* residual) const {
    const T stretch = (1.0 + strain) * (1.0 + preload[0]);
    const T invariant = stretch * stretch + 2.0 / stretch - 3.0;  // I1 - 3
    const T lock = 1.0 - alpha[0] * invariant;
    if (!(lock > 0.0)) return false;
    residual[0] = (mu[0] * (stretch - 1.0 / (stretch * stretch)) / lock - stress_pa) / scale_pa;
    return true;
  }
};

struct Start {
  double mu_pa, alpha, preload;
};

// The starts: the preload at 0 and 0.1, the locking at none and at a quarter, a half and nine tenths of the most the
// last row allows; mu from the middle row's stress at that preload.
std::vector<Start> starts(const CouponTest& test, bool gent) {
  std::vector<Start> out;
  const CouponRow& mid = test.rows[test.rows.size() / 2];
  for (double preload : {0.0, 0.1}) {
    const double last = (1.0 + test.rows.back().engineering_strain) * (1.0 + preload);
    const double most_alpha = 1.0 / (last * last + 2.0 / last - 3.0);
    const double s = (1.0 + mid.engineering_strain) * (1.0 + preload);
    for (double share : gent ? std::vector<double>{0.0, 0.25, 0.5, 0.9} : std::vector<double>{0.0}) {
      const double alpha = share * most_alpha;
      const double mu = mid.nominal_stress_pa * (1.0 - alpha * (s * s + 2.0 / s - 3.0)) / (s - 1.0 / (s * s));
      out.push_back({std::max(mu, 1.0), alpha, preload});
    }
  }
  return out;
}

struct Solved {
  double cost = std::numeric_limits<double>::infinity();
  double mu_pa = 0, alpha = 0, preload = 0;
  double sd[3] = {0, 0, 0};
};

// One start's fit, with its covariance (scaled by the residuals' variance) where the Jacobian allows it.
Solved solveFrom(const CouponTest& test, const Start& start, bool gent) {
  Solved s;
  double mu = start.mu_pa, alpha = start.alpha, preload = start.preload;
  ceres::Problem problem;
  double largest_pa = 0.0;
  for (const CouponRow& r : test.rows) largest_pa = std::max(largest_pa, r.nominal_stress_pa);
  for (const CouponRow& r : test.rows) {
    const double scale = std::max(r.nominal_stress_pa, 1e-3 * largest_pa);  // a zero-stress first row weighs as 0.1 %
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<RelativeStressError, 1, 1, 1, 1>(
                                 new RelativeStressError{r.engineering_strain, r.nominal_stress_pa, scale}),
                             nullptr, &mu, &alpha, &preload);
  }
  problem.SetParameterLowerBound(&mu, 0, 1.0);
  problem.SetParameterLowerBound(&alpha, 0, 0.0);
  problem.SetParameterLowerBound(&preload, 0, 0.0);
  problem.SetParameterUpperBound(&preload, 0, 1.0);
  if (!gent) problem.SetParameterBlockConstant(&alpha);
  ceres::Solver::Options options;
  options.max_num_iterations = 200;
  options.function_tolerance = 1e-14;
  options.parameter_tolerance = 1e-12;
  options.gradient_tolerance = 1e-14;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (!summary.IsSolutionUsable()) return s;
  s.cost = summary.final_cost;
  s.mu_pa = mu, s.alpha = alpha, s.preload = preload;
  ceres::Covariance::Options covariance_options;
  ceres::Covariance covariance(covariance_options);
  std::vector<std::pair<const double*, const double*>> blocks = {{&mu, &mu}, {&preload, &preload}};
  if (gent) blocks.push_back({&alpha, &alpha});
  if (!covariance.Compute(blocks, &problem)) return s;
  const double keys = gent ? 3.0 : 2.0;
  const double variance = 2.0 * summary.final_cost / std::max(1.0, static_cast<double>(test.rows.size()) - keys);
  double c = 0;
  covariance.GetCovarianceBlock(&mu, &mu, &c), s.sd[0] = std::sqrt(c * variance);
  covariance.GetCovarianceBlock(&preload, &preload, &c), s.sd[2] = std::sqrt(c * variance);
  if (gent) covariance.GetCovarianceBlock(&alpha, &alpha, &c), s.sd[1] = std::sqrt(c * variance);
  return s;
}

}  // namespace

double uniaxialNominalStressPa(double stretch, double shear_modulus_pa, double locking_jm) {
  const double invariant = stretch * stretch + 2.0 / stretch - 3.0;
  const double lock = locking_jm > 0.0 ? 1.0 - invariant / locking_jm : 1.0;
  if (!(lock > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return shear_modulus_pa * (stretch - 1.0 / (stretch * stretch)) / lock;
}

CouponFit fitCoupon(const CouponTest& test, bool gent) {
  checkCouponRows(test.rows, test.origin);
  Solved best;
  const std::vector<Start> from = starts(test, gent);
  for (const Start& start : from) {
    const Solved s = solveFrom(test, start, gent);
    if (s.cost < best.cost) best = s;
  }
  if (!std::isfinite(best.cost)) throw ParameterError(test.origin + ": no start of the coupon fit converged");
  CouponFit fit;
  fit.gent = gent;
  fit.starts = static_cast<int>(from.size());
  fit.shear_modulus_pa = best.mu_pa, fit.shear_modulus_sd_pa = best.sd[0];
  fit.preload_strain = best.preload, fit.preload_strain_sd = best.sd[2];
  // J_m = 1 / alpha; alpha at its bound 0 is no locking, written as J_m = 0 (the Neo-Hookean solid).
  fit.wall_locking_jm = best.alpha > 0.0 ? 1.0 / best.alpha : 0.0;
  fit.wall_locking_jm_sd = best.alpha > 0.0 ? best.sd[1] / (best.alpha * best.alpha) : 0.0;
  // A modulus the data do not fix is no reading: most often a strain in percent whose first rows look linear.
  if (!(fit.shear_modulus_sd_pa < fit.shear_modulus_pa)) {
    throw ParameterError(test.origin + ": the coupon does not fix the shear modulus (" +
                         formatMessage(fit.shear_modulus_pa) + " +- " + formatMessage(fit.shear_modulus_sd_pa) +
                         " Pa, one sd); is the strain in percent? Give it as a ratio (0.2 for 20 %), or more of the "
                         "curve");
  }
  // Nor is a lock the data do not reach: a short test's J_m decides whether a wall folds, and the test cannot say.
  if (gent && fit.wall_locking_jm > 0.0 && !(fit.wall_locking_jm_sd < fit.wall_locking_jm)) {
    throw ParameterError(test.origin + ": the coupon does not fix where the elastomer locks (wall_locking_jm " +
                         formatMessage(fit.wall_locking_jm) + " +- " + formatMessage(fit.wall_locking_jm_sd) +
                         ", one sd), which decides whether a wall folds: give the test up to larger strains (the "
                         "walls stretch several times their length), or fit the Neo-Hookean law (--coupon-law "
                         "neo-hookean; Python: law='neo-hookean')");
  }
  double sum = 0.0;
  for (const CouponRow& r : test.rows) {
    const double stretch = (1.0 + r.engineering_strain) * (1.0 + fit.preload_strain);
    const double model = uniaxialNominalStressPa(stretch, fit.shear_modulus_pa, fit.wall_locking_jm);
    fit.model_stress_pa.push_back(model);
    if (!(r.nominal_stress_pa > 0.0)) continue;
    const double e = std::fabs(model - r.nominal_stress_pa) / r.nominal_stress_pa;
    sum += e * e;
    fit.max_relative_error = std::max(fit.max_relative_error, e);
  }
  fit.rms_relative_error = std::sqrt(sum / static_cast<double>(test.rows.size()));
  return fit;
}

std::string couponFitReport(const CouponFit& fit, const CouponTest& test) {
  std::ostringstream s;
  s << std::setprecision(4);
  s << "# elastomer fitted to the coupon test " << test.origin << " (" << test.rows.size() << " rows, strain "
    << test.rows.front().engineering_strain << " to " << test.rows.back().engineering_strain << "), "
    << (fit.gent ? "Gent" : "Neo-Hookean") << ", least squares on the relative stress error, " << fit.starts
    << " starts:\n";
  s << "#   shear_modulus_pa " << fit.shear_modulus_pa << " +- " << fit.shear_modulus_sd_pa << " (one sd)\n";
  if (fit.gent) {
    s << "#   wall_locking_jm " << fit.wall_locking_jm << " +- " << fit.wall_locking_jm_sd
      << (fit.wall_locking_jm == 0.0 ? " (no locking found: Neo-Hookean)" : "") << "\n";
  }
  s << "#   preload strain " << fit.preload_strain << " +- " << fit.preload_strain_sd
    << " (the test's zero taken stretched; not written)\n";
  s << "#   relative stress error: rms " << fit.rms_relative_error << ", largest " << fit.max_relative_error << "\n";
  return s.str();
}

bool parseCouponLaw(const std::string& name) {
  if (name == "gent") return true;
  if (name == "neo-hookean") return false;
  throw ParameterError("the coupon's law must be gent or neo-hookean, got '" + name + "'");
}

std::string couponParameterYaml(RawParameterMap base, const CouponFit& fit, const PressureRange& range) {
  if (FingerParameters::fromRaw(base).wall_law == WallLaw::kPaper) {
    throw ParameterError("a coupon gives the elastomer's shear modulus, and the paper law's shear_modulus_pa is an "
                         "effective stiffness fitted to an actuator: give a parameter file with the membrane or thick "
                         "law (or set wall_law=thick)");
  }
  base["shear_modulus_pa"] = {{fit.shear_modulus_pa}, false};
  base["wall_locking_jm"] = {{fit.wall_locking_jm}, false};
  PressureRange unvalidated = range;  // a coupon is the elastomer's: no actuator has validated this file
  unvalidated.validated_max_gauge_pa = 0.0;
  return parametersToYaml(FingerParameters::fromRaw(base)) + "\n" + rangeToYaml(unvalidated);
}

}  // namespace pneumatic_finger
