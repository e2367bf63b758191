// The calibration's solver: a fit's best point over its keys' whole search box. Internal header of src/calibration.
#pragma once

#include <Eigen/Dense>

#include <utility>
#include <vector>

#include "fit_problem.hpp"

namespace pneumatic_finger {

struct FitSolution {
  Eigen::VectorXd u;       ///< the best point, in the unit cube of FitProblem
  double objective = 0.0;  ///< its objective (max |term| or sum of squares)
};

/// Every point a scan evaluated, with its terms (FitProblem::terms): leave-one-out's folds choose their starts from it.
struct ScanRecord {
  std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> points;
};

/// Global and exact: a coarse scan of the cube (a grid for one key, a Halton sequence for more; no start point to get
/// wrong), then a local solve from each of the best few distinct scan points, the best kept. Least squares are solved
/// by Ceres (Levenberg-Marquardt within the bounds); a minimax by NLopt's SLSQP on its epigraph form (minimise t with
/// every |term| <= t), which is smooth where the largest error is not. @p record, where given, keeps the scan.
/// @throws ParameterError when no point of the scan gives every row a shape
FitSolution solveFit(const FitProblem& problem, CalibrationObjective objective, ScanRecord* record = nullptr);

/// solveFit's scan alone, kept in @p record: where a fit's record is not at hand, leave-one-out's folds start from it.
void scanInto(const FitProblem& problem, CalibrationObjective objective, ScanRecord& record);

/// A leave-one-out fold: @p fold's problem is the full one without one row, whose terms are @p terms from
/// @p first_term of the full problem's. Its starts are the best of the full scan @p full measured without that row
/// (no new scan, and nothing of the held-out row), then solved locally as solveFit does.
FitSolution solveFold(const FitProblem& fold, CalibrationObjective objective, const ScanRecord& full,
                      std::size_t first_term, std::size_t terms);

/// The same for a fold that holds out several rows: @p kept_terms[t] says whether the full problem's term t is the
/// fold's (the held-out rows' terms are not), in order.
FitSolution solveFold(const FitProblem& fold, CalibrationObjective objective, const ScanRecord& full,
                      const std::vector<bool>& kept_terms);



/// How many scan points a fit of @p keys keys takes: 41 for one key, 32 more for each further one.
int scanPoints(std::size_t keys);

}  // namespace pneumatic_finger
