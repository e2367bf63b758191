// The fit as a function: every term a calibration compares (model - measured), at a point of the keys' search box.
// The solvers (solver.cpp) and the uncertainty (calibration_uncertainty.cpp) see the fit only through this. Internal
// header of src/calibration.
#pragma once

#include <Eigen/Dense>

#include <atomic>
#include <mutex>
#include <string>
#include <vector>

#include "fit_space.hpp"
#include "pneumatic_finger/calibration/calibration.hpp"

namespace pneumatic_finger {

/// The objective over @p terms: the largest |term| (minimax), the sum of squares, or the sum of Huber's losses at
/// @p huber_scale (e^2 within it, 2 s |e| - s^2 beyond).
double reduce(const Eigen::VectorXd& terms, CalibrationObjective objective, double huber_scale = 0.0);

/// Huber's scale for @p terms: 1.345 robust standard deviations, 1.4826 times the median |term| (0 for no terms).
double huberScale(const Eigen::VectorXd& terms);

/// The keys' search box, scaled to the unit cube: u_k in [0, 1] is axes[k].lo + u_k (hi - lo) in the key's search
/// coordinate (log10 for mu and J_m). One scale for every key, so that one difference step and one tolerance serve all.
class FitProblem {
 public:
  FitProblem(const FingerParameters& base, const std::vector<std::string>& keys, const std::vector<Measurement>& data,
             CalibrationQuantity quantity, CalibrationProgress progress = {});

  std::size_t keyCount() const { return axes_.size(); }
  /// How many terms every point gives (a row's terms do not depend on the keys): in the compared form, or in the
  /// squares' form (@p squares), where a tip position's distance is its two components, whose squares sum to the
  /// distance's and which, unlike the distance, are smooth where the fit is exact.
  std::size_t termCount(bool squares = false) const { return squares ? square_count_ : term_count_; }
  const std::vector<SearchAxis>& axes() const { return axes_; }
  /// Where row @p row's terms begin among a point's (compared form), and how many it has.
  std::size_t firstTermOf(std::size_t row) const { return row_first_[row]; }
  std::size_t termCountOf(std::size_t row) const { return row_first_[row + 1] - row_first_[row]; }
  /// Where row @p row's terms begin in the squares' form (a row's terms there: a tip position's two components, then
  /// its force's).
  std::size_t firstSquareTermOf(std::size_t row) const { return row_first_square_[row]; }
  /// Which of a row's terms in the squares' form are one error together: a tip position's two components (its first
  /// two, where the row has a shape); every other term alone.
  bool pairsFirstTwo(std::size_t row) const {
    return quantity_ == CalibrationQuantity::kTipPosition && termCountOf(row) < squareTermCountOf(row);
  }
  std::size_t squareTermCountOf(std::size_t row) const {
    return (row + 1 < row_first_square_.size() ? row_first_square_[row + 1] : square_count_) - row_first_square_[row];
  }

  /// The terms at @p u; false where the model gives a row no shape (beyond its limit point with no far branch) or the
  /// point is a wall the law does not allow: no number to compare, which the solvers treat as outside the feasible set.
  bool terms(const Eigen::VectorXd& u, Eigen::VectorXd& out, bool squares = false) const;
  /// The same and d terms / d u, by central differences of step kStep kept inside the cube (one-sided on its faces,
  /// and where a step leaves the rows' shapes; zero where both do). False only where terms() is.
  bool termsAndJacobian(const Eigen::VectorXd& u, Eigen::VectorXd& out, Eigen::MatrixXd& jacobian,
                        bool squares = false) const;
  /// reduce() of the terms (Huber's at no scale: its solver fixes one); +inf where terms() is false.
  double objective(const Eigen::VectorXd& u, CalibrationObjective objective) const;

  FingerParameters parametersAt(const Eigen::VectorXd& u) const;
  /// The keys' values at @p u, in their units, in the order the keys were given.
  std::vector<double> valuesAt(const Eigen::VectorXd& u) const;
  /// Where @p values (in the keys' units) sit in the cube.
  Eigen::VectorXd pointOf(const std::vector<double>& values) const;

  /// Model evaluations so far (a row at a point is one). terms() and report() may be called from several threads.
  long evaluations() const { return evaluations_; }
  /// Tells the progress listener @p step with the evaluations so far, at most every 64th call.
  void report(const std::string& step) const;

  static constexpr double kStep = 1e-6;  ///< the difference step, in the cube's unit (a millionth of each bracket)

 private:
  /// A row's terms, in the compared form or the squares' form.
  std::vector<double> rowTerms(const Residual& r, bool squares) const;

  FingerParameters base_;
  std::vector<SearchAxis> axes_;
  const std::vector<Measurement>* data_;
  CalibrationQuantity quantity_;
  CalibrationProgress progress_;
  std::size_t term_count_ = 0, square_count_ = 0;
  std::vector<std::size_t> row_first_, row_first_square_;
  mutable std::atomic<long> evaluations_{0};
  mutable std::atomic<long> reports_{0};
  mutable std::mutex report_mutex_;  // the listener hears one thread at a time
};

}  // namespace pneumatic_finger
