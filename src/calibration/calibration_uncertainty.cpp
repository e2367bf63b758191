// What a calibration's data can tell (calibration.hpp, calibrationUncertainty): each key's standard deviation from
// the fit's curvature, the keys' correlations, and warnings in plain words.
#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "fit_space.hpp"
#include "pneumatic_finger/calibration/calibration.hpp"

namespace pneumatic_finger {

namespace {

constexpr double kTradeOffCorrelation = 0.95;

// Every compared term of @p parameters against @p data, in one vector (NaN terms kept: the caller checks).
Eigen::VectorXd termsAt(const FingerParameters& parameters, const std::vector<Measurement>& data,
                        CalibrationQuantity quantity) {
  std::vector<double> all;
  for (const Residual& r : residuals(parameters, data)) {
    for (double e : r.terms(quantity)) all.push_back(e);
  }
  return Eigen::Map<const Eigen::VectorXd>(all.data(), static_cast<Eigen::Index>(all.size()));
}

// The search coordinate of @p value on @p axis (log10 for a logarithmic one).
double coordinateOf(const SearchAxis& axis, double value) { return axis.logarithmic ? std::log10(value) : value; }

// d terms / d coordinate for each key by central differences, a step of 1e-4 of the bracket kept inside it.
Eigen::MatrixXd jacobian(const CalibrationResult& fit, const std::vector<SearchAxis>& axes,
                         const std::vector<Measurement>& data, CalibrationQuantity quantity) {
  const Eigen::VectorXd at = termsAt(fit.parameters, data, quantity);
  Eigen::MatrixXd j(at.size(), static_cast<Eigen::Index>(axes.size()));
  for (std::size_t k = 0; k < axes.size(); ++k) {
    const double x = coordinateOf(axes[k], fit.values[k]), h = 1e-4 * (axes[k].hi - axes[k].lo);
    const double lo = std::max(axes[k].lo, x - h), hi = std::min(axes[k].hi, x + h);
    FingerParameters p = fit.parameters;
    setKey(p, axes[k].key, axes[k].toValue(hi));
    const Eigen::VectorXd up = termsAt(p, data, quantity);
    setKey(p, axes[k].key, axes[k].toValue(lo));
    const Eigen::VectorXd down = termsAt(p, data, quantity);
    j.col(static_cast<Eigen::Index>(k)) = (up - down) / (hi - lo);
  }
  return j;
}

std::string boundWarning(const SearchAxis& axis, double value) {
  const double x = coordinateOf(axis, value), width = axis.hi - axis.lo;
  if (x > axis.lo + 1e-6 * width && x < axis.hi - 1e-6 * width) return "";
  std::ostringstream w;
  w << axis.key << " = " << formatMessage(value) << " sits on the " << (x <= axis.lo + 1e-6 * width ? "lower" : "upper")
    << " end of its search range [" << formatMessage(axis.toValue(axis.lo)) << ", " << formatMessage(axis.toValue(axis.hi))
    << "]: the data want it beyond, so the fit is not a minimum in it";
  return w.str();
}

}  // namespace

void calibrationUncertainty(const FingerParameters& base, const std::vector<Measurement>& data,
                            CalibrationQuantity quantity, CalibrationResult& result) {
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
  const Eigen::VectorXd r = termsAt(result.parameters, data, quantity);
  const Eigen::MatrixXd j = jacobian(result, axes, data, quantity);
  const auto m = r.size(), n = static_cast<Eigen::Index>(k);
  if (!r.allFinite() || !j.allFinite() || m <= n) {
    result.warnings.push_back("no uncertainty: " + std::string(m <= n ? "no more compared terms than keys"
                                                                        : "a row has no shape near the fit"));
    return;
  }
  const double s2 = r.squaredNorm() / static_cast<double>(m - n);
  const Eigen::MatrixXd jtj = j.transpose() * j;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(jtj);
  if (lu.rank() < n) {
    result.warnings.push_back("the data do not determine every key: a change of one can be undone by another "
                              "without changing any compared term");
    return;
  }
  const Eigen::MatrixXd cov = s2 * lu.inverse();
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

}  // namespace pneumatic_finger
