// The fit as Ceres sees it. Internal header of src/calibration.
#pragma once

#include <ceres/ceres.h>

#include <Eigen/Dense>

#include "fit_problem.hpp"

namespace pneumatic_finger {

/// Ceres' view of the fit: one residual block, every term (in the squares' form with @p squares: FitProblem::termCount),
/// the Jacobian from FitProblem's differences, each term times its weight in @p weights where given (Huber's
/// reweighting: Ceres' losses act on a whole block, this one's every term at once). The solver's least squares and
/// the uncertainty's covariance use it.
class TermsCost final : public ceres::CostFunction {
 public:
  TermsCost(const FitProblem& problem, bool squares, const Eigen::VectorXd* weights = nullptr)
      : problem_(problem), squares_(squares), weights_(weights) {
    set_num_residuals(static_cast<int>(problem.termCount(squares)));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(problem.keyCount()));
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const auto k = static_cast<Eigen::Index>(problem_.keyCount());
    const Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(parameters[0], k);
    Eigen::VectorXd e;
    Eigen::MatrixXd j;
    const bool ok =
        jacobians && jacobians[0] ? problem_.termsAndJacobian(u, e, j, squares_) : problem_.terms(u, e, squares_);
    problem_.report("least squares");
    if (!ok) return false;
    if (weights_) e.array() *= weights_->array();
    Eigen::Map<Eigen::VectorXd>(residuals, e.size()) = e;
    if (jacobians && jacobians[0]) {
      if (weights_) j.array().colwise() *= weights_->array();
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(jacobians[0], e.size(), k) = j;
    }
    return true;
  }

 private:
  const FitProblem& problem_;
  bool squares_;
  const Eigen::VectorXd* weights_;
};

}  // namespace pneumatic_finger
