// How far a minimax fit's keys scatter under noise (minimax_spread.hpp).
#include "minimax_spread.hpp"

#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace pneumatic_finger {

Eigen::VectorXd linearMinimaxFit(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& e,
                                 const std::vector<ErrorGroup>& groups) {
  const Eigen::Index n = jacobian.cols(), m = jacobian.rows();
  const auto g_count = static_cast<Eigen::Index>(groups.size());
  Eigen::VectorXd weight = Eigen::VectorXd::Constant(g_count, 1.0 / static_cast<double>(g_count));
  Eigen::VectorXd term_weight(m), d = Eigen::VectorXd::Zero(n), error(g_count), left(m);
  double last = HUGE_VAL;
  for (int round = 0; round < 500; ++round) {
    for (Eigen::Index g = 0; g < g_count; ++g) term_weight.segment(groups[g].first, groups[g].count).setConstant(weight[g]);
    const Eigen::MatrixXd weighted = term_weight.asDiagonal() * jacobian;
    d = (jacobian.transpose() * weighted).ldlt().solve(weighted.transpose() * e);
    left.noalias() = e - jacobian * d;
    for (Eigen::Index g = 0; g < g_count; ++g) error[g] = left.segment(groups[g].first, groups[g].count).norm();
    const double largest = error.maxCoeff();
    if (!(largest > 0.0) || std::fabs(last - largest) <= 1e-9 * largest) break;
    last = largest;
    weight = weight.cwiseProduct(error);  // Lawson: the weight follows the error, and the largest errors win
    weight /= weight.sum();
  }
  return d;
}

namespace {

// The linear problem of linearMinimaxFit and its level, for SLSQP: the terms' squares summed, each group's error
// squared at most the level squared.
struct LinearLevel {
  const Eigen::MatrixXd* jacobian;
  const Eigen::VectorXd* e;
  const std::vector<ErrorGroup>* groups;
  double level;
  Eigen::VectorXd left(const double* x) const {
    return *e - *jacobian * Eigen::Map<const Eigen::VectorXd>(x, jacobian->cols());
  }
};

double linearSquares(unsigned n, const double* x, double* gradient, void* data) {
  const auto& l = *static_cast<const LinearLevel*>(data);
  const Eigen::VectorXd r = l.left(x);
  if (gradient) Eigen::Map<Eigen::VectorXd>(gradient, n) = -2.0 * l.jacobian->transpose() * r;
  return r.squaredNorm();
}

void linearLevel(unsigned m, double* result, unsigned n, const double* x, double* gradient, void* data) {
  const auto& l = *static_cast<const LinearLevel*>(data);
  const Eigen::VectorXd r = l.left(x);
  for (unsigned g = 0; g < m; ++g) {
    const ErrorGroup& group = (*l.groups)[g];
    const auto rows = l.jacobian->middleRows(group.first, group.count);
    const auto part = r.segment(group.first, group.count);
    result[g] = part.squaredNorm() - l.level * l.level;
    if (gradient) Eigen::Map<Eigen::VectorXd>(gradient + g * n, n) = -2.0 * rows.transpose() * part;
  }
}

}  // namespace

Eigen::VectorXd linearMinimaxThenSquares(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& e,
                                         const std::vector<ErrorGroup>& groups) {
  Eigen::VectorXd d = linearMinimaxFit(jacobian, e, groups);
  double largest = 0.0;
  const Eigen::VectorXd r = e - jacobian * d;
  for (const ErrorGroup& g : groups) largest = std::max(largest, r.segment(g.first, g.count).norm());
  if (!(largest > 0.0)) return d;
  const auto n = static_cast<unsigned>(d.size());
  LinearLevel l{&jacobian, &e, &groups, largest * (1.0 + 1e-6)};
  nlopt::opt opt(nlopt::LD_SLSQP, n);
  opt.set_min_objective(linearSquares, &l);
  opt.add_inequality_mconstraint(linearLevel, &l, std::vector<double>(groups.size(), 0.0));
  opt.set_xtol_rel(1e-10);
  opt.set_maxeval(200);
  std::vector<double> x(d.data(), d.data() + n);
  double squares = 0.0;
  try {
    opt.optimize(x, squares);
  } catch (const std::exception&) {
    return d;  // a roundoff limit: Lawson's point, on the level
  }
  const Eigen::VectorXd within = Eigen::Map<const Eigen::VectorXd>(x.data(), n);
  return (within - d).cwiseAbs().maxCoeff() < kPlateauStep ? d : within;
}

Eigen::MatrixXd minimaxCovariance(const Eigen::MatrixXd& jacobian, const std::vector<ErrorGroup>& groups, double sigma,
                                  int draws) {
  std::mt19937_64 random(20261207);
  std::normal_distribution<double> noise(0.0, sigma);
  const Eigen::Index n = jacobian.cols();
  Eigen::MatrixXd fits(draws, n);
  for (int k = 0; k < draws; ++k) {
    Eigen::VectorXd e(jacobian.rows());
    for (Eigen::Index i = 0; i < e.size(); ++i) e[i] = noise(random);
    fits.row(k) = linearMinimaxThenSquares(jacobian, e, groups).transpose();
  }
  const Eigen::MatrixXd centred = fits.rowwise() - fits.colwise().mean();
  return centred.transpose() * centred / static_cast<double>(draws - 1);
}

}  // namespace pneumatic_finger
