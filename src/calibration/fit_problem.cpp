#include "fit_problem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace pneumatic_finger {

namespace {
constexpr double kHuberK = 1.345, kMadToSigma = 1.4826;  // Huber's 95 %-efficient constant; MAD to sigma (normal)
}  // namespace

FitProblem::FitProblem(const FingerParameters& base, const std::vector<std::string>& keys,
                       const std::vector<Measurement>& data, CalibrationQuantity quantity, CalibrationProgress progress)
    : base_(base), data_(&data), quantity_(quantity), progress_(std::move(progress)) {
  for (const std::string& k : keys) axes_.push_back(axisFor(k, base));
  // A row's terms are as many at every point: count them at the base, shaped or not.
  row_first_.push_back(0);
  for (const Residual& r : residuals(base, data, quantity)) {
    term_count_ += r.terms(quantity).size();
    square_count_ += rowTerms(r, true).size();
    row_first_.push_back(term_count_);
    row_first_square_.push_back(square_count_ - rowTerms(r, true).size());
  }
}

std::vector<double> FitProblem::rowTerms(const Residual& r, bool squares) const {
  std::vector<double> row = r.terms(quantity_);
  if (!squares || quantity_ != CalibrationQuantity::kTipPosition || r.force_only) return row;
  row[0] = r.model_tip_x_m - r.measured_tip_x_m;  // the distance, first, as its two components
  row.insert(row.begin() + 1, r.model_tip_y_m - r.measured_tip_y_m);
  return row;
}

FingerParameters FitProblem::parametersAt(const Eigen::VectorXd& u) const {
  FingerParameters p = base_;
  for (std::size_t k = 0; k < axes_.size(); ++k) {
    const SearchAxis& a = axes_[k];
    setKey(p, a.key, a.toValue(a.lo + u[static_cast<Eigen::Index>(k)] * (a.hi - a.lo)));
  }
  return p;
}

std::vector<double> FitProblem::valuesAt(const Eigen::VectorXd& u) const {
  std::vector<double> values;
  for (std::size_t k = 0; k < axes_.size(); ++k) {
    const SearchAxis& a = axes_[k];
    values.push_back(a.toValue(a.lo + u[static_cast<Eigen::Index>(k)] * (a.hi - a.lo)));
  }
  return values;
}

Eigen::VectorXd FitProblem::pointOf(const std::vector<double>& values) const {
  Eigen::VectorXd u(static_cast<Eigen::Index>(axes_.size()));
  for (std::size_t k = 0; k < axes_.size(); ++k) {
    const SearchAxis& a = axes_[k];
    const double x = a.logarithmic ? std::log10(values[k]) : values[k];
    u[static_cast<Eigen::Index>(k)] = std::clamp((x - a.lo) / (a.hi - a.lo), 0.0, 1.0);
  }
  return u;
}

bool FitProblem::terms(const Eigen::VectorXd& u, Eigen::VectorXd& out, bool squares) const {
  FingerParameters p;
  try {
    p = parametersAt(u);
  } catch (const ParameterError&) {
    return false;  // a fitted drawing the rule refuses (a body narrower than its cavities): no point of the fit
  }
  // The paper law's wall is bent by its root below the chamber's top: b <= L (docs/MODEL.md).
  for (std::size_t i = 0; p.wall_law == WallLaw::kPaper && i < p.chamber_height_m.size(); ++i) {
    if (p.wall_critical_height_m[i] > p.chamber_height_m[i]) return false;
  }
  evaluations_ += static_cast<long>(data_->size());
  out.resize(static_cast<Eigen::Index>(termCount(squares)));
  Eigen::Index i = 0;
  for (const Residual& r : residuals(p, *data_, quantity_)) {
    for (double e : rowTerms(r, squares)) {
      if (!std::isfinite(e)) return false;  // no shape (NaN), or a pressure without bound
      out[i++] = e;
    }
  }
  return true;
}

bool FitProblem::termsAndJacobian(const Eigen::VectorXd& u, Eigen::VectorXd& out, Eigen::MatrixXd& jacobian,
                                  bool squares) const {
  if (!terms(u, out, squares)) return false;
  jacobian.resize(out.size(), u.size());
  Eigen::VectorXd up, down;
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    Eigen::VectorXd hi = u, lo = u;
    hi[k] = std::min(1.0, u[k] + kStep);
    lo[k] = std::max(0.0, u[k] - kStep);
    // One-sided where a step leaves the shaped rows (the point sits by a row's limit point): the side that has them.
    // Where neither side has them, the key cannot move here: its column is zero, and the solver leaves it.
    const bool above = terms(hi, up, squares), below = terms(lo, down, squares);
    if (!above) hi = u, up = out;
    if (!below) lo = u, down = out;
    jacobian.col(k).setZero();
    if (hi[k] > lo[k]) jacobian.col(k) = (up - down) / (hi[k] - lo[k]);
  }
  return true;
}

double FitProblem::objective(const Eigen::VectorXd& u, CalibrationObjective objective) const {
  Eigen::VectorXd e;
  if (!terms(u, e)) return std::numeric_limits<double>::infinity();
  return reduce(e, objective);
}

void FitProblem::report(const std::string& step) const {
  // Every 64th call: the report's words cost more than a small data set's residuals.
  if (!progress_ || ++reports_ % 64 != 0) return;
  const std::lock_guard<std::mutex> lock(report_mutex_);
  progress_(step + ": " + std::to_string(evaluations_.load()) + " model evaluations");
}

double reduce(const Eigen::VectorXd& terms, CalibrationObjective objective, double huber_scale) {
  if (terms.size() == 0) return 0.0;
  if (objective == CalibrationObjective::kMinimax) return terms.cwiseAbs().maxCoeff();
  if (objective == CalibrationObjective::kLeastSquares) return terms.squaredNorm();
  double sum = 0.0;
  for (double e : terms) {
    const double a = std::fabs(e);
    sum += a <= huber_scale ? a * a : 2.0 * huber_scale * a - huber_scale * huber_scale;
  }
  return sum;
}

double huberScale(const Eigen::VectorXd& terms) {
  if (terms.size() == 0) return 0.0;
  std::vector<double> a(terms.data(), terms.data() + terms.size());
  for (double& x : a) x = std::fabs(x);
  std::nth_element(a.begin(), a.begin() + static_cast<long>(a.size() / 2), a.end());
  return kHuberK * kMadToSigma * a[a.size() / 2];
}

}  // namespace pneumatic_finger
