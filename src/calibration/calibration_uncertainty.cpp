// What a calibration's data can tell (calibration.hpp, calibrationUncertainty): each key's standard deviation from
// the fit's curvature, the keys' correlations, and warnings in plain words.
#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "fit_problem.hpp"
#include "fit_space.hpp"
#include "minimax_spread.hpp"
#include "terms_cost.hpp"
#include "pneumatic_finger/calibration/calibration.hpp"

namespace pneumatic_finger {

namespace {

constexpr double kTradeOffCorrelation = 0.95;

// (J^T J)^-1 at @p u by Ceres' covariance (a dense SVD, which finds a rank the data leave short), in the unit cube's
// coordinates; false where the data do not determine every key.
bool unscaledCovariance(const FitProblem& problem, Eigen::VectorXd u, const Eigen::MatrixXd& jacobian,
                        Eigen::MatrixXd& covariance) {
  // Ceres' own test, asked first: it logs an error where J^T J's reciprocal condition number is below this.
  constexpr double kMinReciprocalCondition = 1e-14;
  const Eigen::VectorXd sigma = Eigen::JacobiSVD<Eigen::MatrixXd>(jacobian).singularValues();
  if (!(sigma.size() > 0 && sigma[sigma.size() - 1] * sigma[sigma.size() - 1] >
                                kMinReciprocalCondition * sigma[0] * sigma[0])) {
    return false;
  }
  ceres::Problem at;
  at.AddResidualBlock(new TermsCost(problem, true), nullptr, u.data());
  ceres::Covariance::Options options;
  options.algorithm_type = ceres::DENSE_SVD;
  options.min_reciprocal_condition_number = kMinReciprocalCondition;
  ceres::Covariance c(options);
  const std::vector<std::pair<const double*, const double*>> blocks = {{u.data(), u.data()}};
  if (!c.Compute(blocks, &at)) return false;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> block(u.size(), u.size());
  c.GetCovarianceBlock(u.data(), u.data(), block.data());
  covariance = block;
  return true;
}

// The errors a minimax fit bounds, in the squares' form's terms: a tip position's two components as one distance,
// every other term alone.
std::vector<ErrorGroup> errorGroups(const FitProblem& problem, std::size_t rows) {
  std::vector<ErrorGroup> groups;
  for (std::size_t row = 0; row < rows; ++row) {
    auto first = static_cast<Eigen::Index>(problem.firstSquareTermOf(row));
    const auto last = first + static_cast<Eigen::Index>(problem.squareTermCountOf(row));
    if (problem.pairsFirstTwo(row)) groups.push_back({first, 2}), first += 2;
    for (; first < last; ++first) groups.push_back({first, 1});
  }
  return groups;
}

// Each key's sd and the keys' correlations from @p cube, their covariance in the unit cube's coordinates (each to its
// search coordinate by its bracket's width), and a warning for each pair that trades off.
void fillFromCovariance(const std::vector<SearchAxis>& axes, const Eigen::MatrixXd& cube, CalibrationResult& result) {
  const std::size_t k = axes.size();
  Eigen::VectorXd width(static_cast<Eigen::Index>(k));
  for (std::size_t a = 0; a < k; ++a) width[static_cast<Eigen::Index>(a)] = axes[a].hi - axes[a].lo;
  const Eigen::MatrixXd cov = width.asDiagonal() * cube * width.asDiagonal();
  for (std::size_t a = 0; a < k; ++a) {
    const auto ia = static_cast<Eigen::Index>(a);
    const double sd = std::sqrt(cov(ia, ia));  // in the search coordinate
    result.uncertainty[a] = axes[a].logarithmic ? result.values[a] * std::log(10.0) * sd : sd;
    for (std::size_t b = 0; b < k; ++b) {
      const auto ib = static_cast<Eigen::Index>(b);
      result.correlation[a * k + b] = cov(ia, ib) / std::sqrt(cov(ia, ia) * cov(ib, ib));
    }
  }
  for (std::size_t a = 0; a < k; ++a) {
    for (std::size_t b = a + 1; b < k; ++b) {
      const double c = result.correlation[a * k + b];
      if (!(std::fabs(c) > kTradeOffCorrelation)) continue;
      std::ostringstream w;
      w << result.keys[a] << " and " << result.keys[b] << " trade off (correlation " << std::fixed;
      w.precision(3);
      w << c << "): the data fix a combination of the two better than either; their values are uncertain together";
      result.warnings.push_back(w.str());
    }
  }
}

}  // namespace

void calibrationUncertainty(const FingerParameters& base, const std::vector<Measurement>& data,
                            CalibrationQuantity quantity, CalibrationObjective objective, CalibrationResult& result) {
  const std::size_t k = result.keys.size();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  result.uncertainty.assign(k, nan);
  result.correlation.assign(k * k, nan);
  result.warnings.clear();
  std::vector<SearchAxis> axes;
  for (const std::string& key : result.keys) axes.push_back(axisFor(key, base));
  for (std::size_t i = 0; i < k; ++i) {
    const std::string w = boundWarning(axes[i], result.values[i]);
    if (!w.empty()) result.warnings.push_back(w);
  }
  const FitProblem problem(base, result.keys, data, quantity);
  const Eigen::VectorXd u = problem.pointOf(result.values);
  Eigen::VectorXd r;
  Eigen::MatrixXd j, unscaled;
  const auto m = static_cast<Eigen::Index>(problem.termCount(true)), n = static_cast<Eigen::Index>(k);
  if (!problem.termsAndJacobian(u, r, j, true) || m <= n) {
    result.warnings.push_back("no uncertainty: " + std::string(m <= n ? "no more compared terms than keys"
                                                                        : "a row has no shape near the fit"));
    return;
  }
  if (!unscaledCovariance(problem, u, j, unscaled)) {
    result.warnings.push_back("the data do not determine every key: a change of one can be undone by another "
                              "without changing any compared term");
    return;
  }
  // The terms' own scatter: s^2 = the sum of squares left once the keys' own directions are taken out (the residual
  // of a least-squares step from the fit; the fit's own residual where it is a least-squares fit), over nu = terms -
  // keys. That scatter is itself estimated: an error over it scatters as Student's t, whose standard deviation is
  // sqrt(nu / (nu - 2)) times the normal's (1.15 for ten tip angles and two keys), so the bar is widened by that much
  // and one sd means one sd. With nu <= 2 it has no standard deviation: the correlations alone (they need no scale).
  const Eigen::VectorXd left = r - j * (unscaled * (j.transpose() * r));
  const auto nu = static_cast<double>(m - n);
  const bool scaled = nu > 2.0;
  const double s2 = scaled ? left.squaredNorm() / nu * (nu / (nu - 2.0)) : 1.0;
  // Least squares (and Huber's, within 5 % of it on normal noise): s^2 (J^T J)^-1. Minimax: its own spread, the
  // linearised fit refitted to draws of that noise.
  const Eigen::MatrixXd cube = objective == CalibrationObjective::kMinimax
                                   ? minimaxCovariance(j, errorGroups(problem, data.size()), std::sqrt(s2))
                                   : Eigen::MatrixXd(s2 * unscaled);
  fillFromCovariance(axes, cube, result);
  if (!scaled) {
    result.uncertainty.assign(k, nan);
    result.warnings.push_back("no standard deviation: the data's scatter needs three compared terms more than keys "
                              "(these data have " + std::to_string(m) + " for " + std::to_string(k) + ")");
  }
}

}  // namespace pneumatic_finger
