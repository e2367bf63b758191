// How far a minimax fit's keys scatter under noise (calibration_uncertainty.cpp). A minimax fit has no covariance of
// its own, and the least-squares one understates its spread (it follows the few largest errors, not all of them):
// its linearisation about the optimum is refitted to many draws of the noise instead, a parametric bootstrap.
// Internal header of src/calibration.
#pragma once

#include <Eigen/Dense>

#include <vector>

namespace pneumatic_finger {

/// A plateau is a minimax level wider than this, in the keys' unit cube (a ten-thousandth of each bracket): the
/// least squares within the level moves the fit only where it is one (solver.cpp, linearMinimaxThenSquares).
inline constexpr double kPlateauStep = 1e-4;

/// One error a minimax fit bounds: @p count terms from @p first (1, or 2 for a tip position's components, whose
/// distance is the error).
struct ErrorGroup {
  Eigen::Index first = 0;
  Eigen::Index count = 1;
};

/// The linear minimax fit: the d that minimises the largest |e_g - J_g d| over the groups (the Euclidean norm of a
/// group's terms), by Lawson's reweighted least squares (each group's weight times its error, until the largest error
/// settles to 1e-9 of itself or 500 rounds).
Eigen::VectorXd linearMinimaxFit(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& e,
                                 const std::vector<ErrorGroup>& groups);

/// The fit's own tie-break as well: linearMinimaxFit, then the least squares among the points whose groups' errors are
/// at most its largest, a millionth above it (SLSQP), where it moves by kPlateauStep or more, as the solver does on a
/// plateau (solver.cpp).
Eigen::VectorXd linearMinimaxThenSquares(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& e,
                                         const std::vector<ErrorGroup>& groups);

/// The keys' covariance (in the jacobian's coordinates) of the minimax fit to the terms whose derivatives are
/// @p jacobian, each term with normal noise of sd @p sigma: the covariance of linearMinimaxFit over @p draws draws of
/// that noise (linearMinimaxThenSquares; a fixed seed: the same answer on every run).
Eigen::MatrixXd minimaxCovariance(const Eigen::MatrixXd& jacobian, const std::vector<ErrorGroup>& groups, double sigma,
                                  int draws = 200);

}  // namespace pneumatic_finger
