#include "solver.hpp"

#include "every_core.hpp"
#include "minimax_spread.hpp"
#include "terms_cost.hpp"

#include <ceres/ceres.h>
#include <nlopt.hpp>

#include "pneumatic_finger/core/golden_section.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace pneumatic_finger {

namespace {

// Local solves from the best kStarts distinct scan points. Three under-solved a fold of the ribbed segment's
// leave-one-out (its optimum lay in the basin of the fourth); six, the ribbed segment's Gent membrane fitted by volume
// (mu, c, J_m, least squares, in scripts/accuracy_volume.py: its optimum lay in the basin of the seventh, 4 % lower).
constexpr std::size_t kStarts = 8;
constexpr double kDistinct = 0.15;           // scan points closer than this (in every key, unit cube) are one start
constexpr int kIterations = 100, kCandidateIterations = 20;  // Levenberg-Marquardt's, as the fit and as a candidate
constexpr double kTolerance = 1e-12;  // the local solvers' relative tolerances, as the old golden sections'

// The i-th point (from 1) of the Halton sequence in base @p base: well spread in any number of dimensions.
double halton(int i, int base) {
  double f = 1.0, x = 0.0;
  for (; i > 0; i /= base) {
    f /= base;
    x += f * (i % base);
  }
  return x;
}

// scanPoints(dims) points of the cube [0, 1]^dims: a grid for one dimension, a Halton sequence for more, with the
// cube's corners (a Halton set never reaches a face, where a key such as a gap of 0 may have its optimum's basin).
// Not the start parameters' point: the fit does not depend on where it starts.
std::vector<Eigen::VectorXd> scanCube(std::size_t dims) {
  static constexpr int kPrimes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37};
  const int n = scanPoints(dims);
  std::vector<Eigen::VectorXd> points;
  for (unsigned corner = 0; dims > 1 && corner < (1U << dims); ++corner) {
    Eigen::VectorXd u(static_cast<Eigen::Index>(dims));
    for (std::size_t k = 0; k < dims; ++k) u[static_cast<Eigen::Index>(k)] = (corner >> k) & 1U ? 1.0 : 0.0;
    points.push_back(std::move(u));
  }
  for (int i = 0; i < n; ++i) {
    Eigen::VectorXd u(static_cast<Eigen::Index>(dims));
    for (std::size_t k = 0; k < dims; ++k) {
      u[static_cast<Eigen::Index>(k)] = dims == 1 ? static_cast<double>(i) / (n - 1) : halton(i + 1, kPrimes[k % 12]);
    }
    points.push_back(std::move(u));
  }
  return points;
}

// The scan's points, each with its objective. The shear modulus, where it is fitted with other keys, is not scanned but
// solved at each point of the others (a profile): every bend falls as mu rises, so along mu the objective is
// quasi-convex, and its valley, a fraction of a decade wide in 7, falls between any coarse grid's points. A coarse
// line of kMuLine points brackets it, a golden section to 1e-4 of the range finds it.
// One point of the scan: @p v, the point of the keys other than mu where mu is profiled (@p m its index), else of
// every key; mu, where profiled, solved along its line: every bend falls as mu rises, so along mu the objective is
// quasi-convex, and its valley, a fraction of a decade wide in 7, falls between any coarse grid's points. A coarse line
// of kMuLine points brackets it, a golden section to 1e-4 of the range finds it. The objective and the whole point.
std::pair<double, Eigen::VectorXd> scanPoint(const FitProblem& problem, CalibrationObjective objective,
                                             const Eigen::VectorXd& v, Eigen::Index m, bool profile,
                                             ScanRecord* record) {
  constexpr int kMuLine = 17;
  Eigen::VectorXd u(static_cast<Eigen::Index>(problem.keyCount()));
  if (profile) u << v.head(m), 0.0, v.tail(v.size() - m); else u = v;
  auto at = [&](double x) {
    if (profile) u[m] = x;
    problem.report("scan");
    Eigen::VectorXd e;
    if (!problem.terms(u, e)) return std::numeric_limits<double>::infinity();
    if (record) record->points.emplace_back(u, e);
    return reduce(e, objective);
  };
  double best_x = 0.0, best = at(0.0);
  for (int i = 1; profile && i < kMuLine; ++i) {
    const double x = static_cast<double>(i) / (kMuLine - 1), value = at(x);
    if (value < best) best = value, best_x = x;
  }
  if (profile && std::isfinite(best)) {
    const double w = 1.0 / (kMuLine - 1);
    const GoldenMinimum g = goldenSection(at, std::max(0.0, best_x - w), std::min(1.0, best_x + w), 40,
                                          [](double a, double b, double, double) { return b - a > 1e-4; });
    if (g.value < best) best = g.value, best_x = g.x;
  }
  if (profile) u[m] = best_x;
  return {best, u};
}

// scanPoint at each of @p points, on every core, in their order; each point's record appended in that order too.
std::vector<std::pair<double, Eigen::VectorXd>> scanEach(const FitProblem& problem, CalibrationObjective objective,
                                                         const std::vector<Eigen::VectorXd>& points, Eigen::Index m,
                                                         bool profile, ScanRecord* record) {
  std::vector<std::pair<double, Eigen::VectorXd>> at(points.size());
  std::vector<ScanRecord> records(record ? points.size() : 0);
  onEveryCore(points.size(), [&](std::size_t i) {
    at[i] = scanPoint(problem, objective, points[i], m, profile, record ? &records[i] : nullptr);
  });
  for (ScanRecord& r : records) {
    for (auto& p : r.points) record->points.push_back(std::move(p));
  }
  return at;
}

// The scan's points, each with its objective: the cube's (scanCube), then, with two or more scanned dimensions, a
// line of 41 points along each through the best of them (a basin narrow in one key, as the gas's by a face, is missed
// by a sparse set and found along a line), then a golden section along each. The shear modulus, where it is fitted
// with other keys, is profiled.
std::vector<std::pair<double, Eigen::VectorXd>> scan(const FitProblem& problem, CalibrationObjective objective,
                                                     ScanRecord* record) {
  const auto& axes = problem.axes();
  const auto mu = std::find_if(axes.begin(), axes.end(), [](const SearchAxis& a) { return a.key == "shear_modulus_pa"; });
  const bool profile = mu != axes.end() && axes.size() > 1;
  const auto m = static_cast<Eigen::Index>(mu - axes.begin());
  const auto dims = static_cast<Eigen::Index>(axes.size()) - (profile ? 1 : 0);
  std::vector<std::pair<double, Eigen::VectorXd>> scanned;
  double best = std::numeric_limits<double>::infinity();
  Eigen::VectorXd best_v = Eigen::VectorXd::Zero(dims);
  const std::vector<Eigen::VectorXd> cube = scanCube(static_cast<std::size_t>(dims));
  auto at_cube = scanEach(problem, objective, cube, m, profile, record);
  for (std::size_t i = 0; i < cube.size(); ++i) {
    if (at_cube[i].first < best) best = at_cube[i].first, best_v = cube[i];
    if (std::isfinite(at_cube[i].first)) scanned.push_back(std::move(at_cube[i]));
  }
  constexpr int kLine = 41;
  for (Eigen::Index d = 0; dims > 1 && std::isfinite(best) && d < dims; ++d) {
    std::vector<Eigen::VectorXd> line(kLine, best_v);  // the best point, moved along key d
    for (int i = 0; i < kLine; ++i) line[static_cast<std::size_t>(i)][d] = static_cast<double>(i) / (kLine - 1);
    auto at_line = scanEach(problem, objective, line, m, profile, record);
    for (std::size_t i = 0; i < line.size(); ++i) {
      const double value = at_line[i].first;
      if (std::isfinite(value)) scanned.push_back(std::move(at_line[i]));
      if (value < best) best = value, best_v = line[i];
    }
  }
  // Then a golden section along each scanned key, a line's step either side of the best: a basin narrower than the
  // step (a gap that lets one more row touch) lies between two points of a plateau.
  for (Eigen::Index d = 0; dims > 0 && std::isfinite(best) && d < dims; ++d) {
    Eigen::VectorXd v = best_v;
    const auto along = [&](double x) {
      v[d] = x;
      auto point = scanPoint(problem, objective, v, m, profile, record);
      if (std::isfinite(point.first)) scanned.push_back(point);
      return point.first;
    };
    const double w = 1.0 / (kLine - 1);
    goldenSection(along, std::max(0.0, best_v[d] - w), std::min(1.0, best_v[d] + w), 30,
                  [](double a, double b, double, double) { return b - a > 1e-6; });
  }
  return scanned;
}

// NLopt's Subplex on the objective itself, from @p start: a local search that needs no derivative.
FitSolution derivativeFreeFrom(const FitProblem& problem, const Eigen::VectorXd& start, CalibrationObjective objective) {
  const auto k = static_cast<unsigned>(start.size());
  struct Goal {
    const FitProblem* problem;
    CalibrationObjective objective;
  } goal{&problem, objective};
  nlopt::opt opt(nlopt::LN_SBPLX, k);
  opt.set_lower_bounds(std::vector<double>(k, 0.0));
  opt.set_upper_bounds(std::vector<double>(k, 1.0));
  opt.set_min_objective(
      [](unsigned n, const double* x, double*, void* data) {
        const auto& g = *static_cast<Goal*>(data);
        const double value = g.problem->objective(Eigen::Map<const Eigen::VectorXd>(x, n), g.objective);
        g.problem->report("derivative-free");
        return std::isfinite(value) ? value : HUGE_VAL;
      },
      &goal);
  opt.set_xtol_rel(kTolerance);
  opt.set_maxeval(100 * static_cast<int>(k));
  opt.set_initial_step(std::vector<double>(k, 0.5 / (scanPoints(k) - 1)));
  std::vector<double> x(start.data(), start.data() + k);
  double value = HUGE_VAL;
  try {
    opt.optimize(x, value);
  } catch (const std::exception&) {
    // A roundoff limit: the point reached stands.
  }
  const Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(x.data(), k);
  return {u, problem.objective(u, objective)};
}

FitSolution leastSquaresFrom(const FitProblem& problem, const Eigen::VectorXd& start, int iterations,
                             const Eigen::VectorXd* weights = nullptr) {
  // A start on a face of the cube, moved a thousandth inside it: room for the differences on both sides.
  Eigen::VectorXd u = start.cwiseMax(1e-3).cwiseMin(1.0 - 1e-3);

  ceres::Problem solve;
  // Weighted (Huber's reweighting) in the compared form, whose terms the weights are of; else the squares' form.
  solve.AddResidualBlock(new TermsCost(problem, weights == nullptr, weights), nullptr, u.data());
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    solve.SetParameterLowerBound(u.data(), static_cast<int>(k), 0.0);
    solve.SetParameterUpperBound(u.data(), static_cast<int>(k), 1.0);
  }
  ceres::Solver::Options options;
  options.max_num_iterations = iterations;
  options.function_tolerance = kTolerance;
  options.parameter_tolerance = kTolerance;
  options.gradient_tolerance = 1e-16;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &solve, &summary);
  return {u, problem.objective(u, CalibrationObjective::kLeastSquares)};
}

// Huber's robust fit from the least-squares optimum @p u: the scale from its terms, then iteratively reweighted least
// squares (each term weighted by min(1, s / |e|), whose fixed point is Huber's optimum) until the weights settle.
FitSolution huberFrom(const FitProblem& problem, const Eigen::VectorXd& u) {
  constexpr int kRounds = 30;
  Eigen::VectorXd e;
  if (!problem.terms(u, e)) return {u, std::numeric_limits<double>::infinity()};
  const double scale = huberScale(e);
  FitSolution at{u, reduce(e, CalibrationObjective::kHuber, scale)};
  if (!(scale > 0.0)) return at;  // an exact fit: nothing is an outlier
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(e.size());
  for (int round = 0; round < kRounds; ++round) {
    const Eigen::VectorXd last = weights;
    weights = (scale / e.array().abs().max(scale)).sqrt();  // sqrt(min(1, s/|e|)): squared, the weight itself
    if (round > 0 && (weights - last).cwiseAbs().maxCoeff() < 1e-12) break;
    const FitSolution next = leastSquaresFrom(problem, at.u, kIterations, &weights);
    if (!problem.terms(next.u, e)) break;
    at = {next.u, reduce(e, CalibrationObjective::kHuber, scale)};
  }
  return at;
}

// The minimax's epigraph: the point (u, t) with every |term| <= t, t least. The best point any evaluation saw is kept
// (SLSQP may end on a roundoff limit a step past it).
struct Epigraph {
  const FitProblem* problem;
  FitSolution best;
  // The last point's terms, and their Jacobian where it was asked for. SLSQP often asks again at the same keys; the
  // same keys give the same terms, so those calls cost nothing.
  Eigen::VectorXd last_u, e;
  Eigen::MatrixXd j;
  bool ok = false, has_jacobian = false;
};

void epigraphConstraints(unsigned m, double* result, unsigned n, const double* x, double* gradient, void* data) {
  auto& g = *static_cast<Epigraph*>(data);
  const auto k = static_cast<Eigen::Index>(n - 1);
  const Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(x, k);
  const double t = x[n - 1];
  const bool same = g.last_u.size() == u.size() && g.last_u == u;
  if (!same || (gradient && !g.has_jacobian)) {
    g.ok = gradient ? g.problem->termsAndJacobian(u, g.e, g.j) : g.problem->terms(u, g.e);
    g.has_jacobian = gradient != nullptr;
    g.last_u = u;
  }
  const bool ok = g.ok;
  const Eigen::VectorXd& e = g.e;
  const Eigen::MatrixXd& j = g.j;
  g.problem->report("minimax");
  const unsigned terms = m / 2;
  for (unsigned i = 0; i < terms; ++i) {
    // No shape: far outside the feasible set, so that the line search steps back.
    result[i] = ok ? e[i] - t : 1e6;
    result[terms + i] = ok ? -e[i] - t : 1e6;
    for (unsigned c = 0; gradient && c < n; ++c) {
      const double d = ok && c + 1 < n ? j(i, c) : 0.0;
      gradient[i * n + c] = c + 1 < n ? d : -1.0;
      gradient[(terms + i) * n + c] = c + 1 < n ? -d : -1.0;
    }
  }
  if (ok && e.cwiseAbs().maxCoeff() < g.best.objective) g.best = {u, e.cwiseAbs().maxCoeff()};
}

double epigraphObjective(unsigned n, const double* x, double* gradient, void*) {
  for (unsigned c = 0; gradient && c < n; ++c) gradient[c] = c + 1 < n ? 0.0 : 1.0;
  return x[n - 1];
}

FitSolution minimaxFrom(const FitProblem& problem, const Eigen::VectorXd& start, double start_objective) {
  // A start that fits every row exactly (data made by the model, a scan point on the truth) is the optimum; SLSQP
  // would be given a zero step for the bound t, which NLopt refuses by throwing.
  if (!(start_objective > 0.0)) return {start, start_objective};
  const auto k = static_cast<unsigned>(start.size());
  Epigraph g{&problem, {start, start_objective}, {}, {}, {}};
  nlopt::opt opt(nlopt::LD_SLSQP, k + 1);
  std::vector<double> lower(k + 1, 0.0), upper(k + 1, 1.0);
  upper[k] = HUGE_VAL;
  opt.set_lower_bounds(lower);
  opt.set_upper_bounds(upper);
  opt.set_min_objective(epigraphObjective, nullptr);
  const std::vector<double> tolerances(2 * problem.termCount(), 0.0);
  opt.add_inequality_mconstraint(epigraphConstraints, &g, tolerances);
  opt.set_xtol_rel(kTolerance);
  opt.set_maxeval(100);
  std::vector<double> x(start.data(), start.data() + k);
  x.push_back(start_objective);
  std::vector<double> step(k + 1, 0.5 / (scanPoints(k) - 1));
  step[k] = 0.5 * start_objective;
  opt.set_initial_step(step);
  double t = 0.0;
  try {
    opt.optimize(x, t);
  } catch (const std::exception&) {
    // A roundoff limit or a failed line search: the best point seen stands.
  }
  return g.best;
}

// The least squares within the minimax's level: the point whose terms' squares sum least among those whose largest
// |term| is at most the minimax's, a millionth above it. Where the largest error cannot move (a term no key changes,
// as a bend set by a volume barely depends on mu), the minimax's optimum is a plateau, a solver stops anywhere on it,
// and neither the fit nor its error bar would be one number; elsewhere the level holds the optimum alone, and the
// point stands.
struct Level {
  const FitProblem* problem;
  double t;
  Eigen::VectorXd last_u, e;
  Eigen::MatrixXd j;
  bool ok = false;
  // The terms and their Jacobian at @p x, asked once per point (the objective and the constraints share them).
  void at(const double* x, unsigned n) {
    const Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(x, n);
    if (last_u.size() == u.size() && last_u == u) return;
    ok = problem->termsAndJacobian(u, e, j);
    last_u = u;
  }
};

double levelObjective(unsigned n, const double* x, double* gradient, void* data) {
  auto& l = *static_cast<Level*>(data);
  l.at(x, n);
  for (unsigned c = 0; gradient && c < n; ++c) gradient[c] = l.ok ? 2.0 * l.j.col(c).dot(l.e) : 0.0;
  return l.ok ? l.e.squaredNorm() : HUGE_VAL;
}

void levelConstraints(unsigned m, double* result, unsigned n, const double* x, double* gradient, void* data) {
  auto& l = *static_cast<Level*>(data);
  l.at(x, n);
  const unsigned terms = m / 2;
  for (unsigned i = 0; i < terms; ++i) {
    result[i] = l.ok ? l.e[i] - l.t : 1e6;
    result[terms + i] = l.ok ? -l.e[i] - l.t : 1e6;
    for (unsigned c = 0; gradient && c < n; ++c) {
      gradient[i * n + c] = l.ok ? l.j(i, c) : 0.0;
      gradient[(terms + i) * n + c] = l.ok ? -l.j(i, c) : 0.0;
    }
  }
}

FitSolution leastSquaresWithinLevel(const FitProblem& problem, const FitSolution& minimax) {
  if (!(minimax.objective > 0.0)) return minimax;  // an exact fit: one point
  const auto k = static_cast<unsigned>(minimax.u.size());
  const double level = minimax.objective * (1.0 + 1e-6);
  Level l{&problem, level, {}, {}, {}};
  nlopt::opt opt(nlopt::LD_SLSQP, k);
  opt.set_lower_bounds(std::vector<double>(k, 0.0));
  opt.set_upper_bounds(std::vector<double>(k, 1.0));
  opt.set_min_objective(levelObjective, &l);
  opt.add_inequality_mconstraint(levelConstraints, &l, std::vector<double>(2 * problem.termCount(), 0.0));
  opt.set_xtol_rel(kTolerance);
  opt.set_maxeval(100);
  std::vector<double> x(minimax.u.data(), minimax.u.data() + k);
  double squares = 0.0;
  try {
    opt.optimize(x, squares);
  } catch (const std::exception&) {
    // A roundoff limit: the point reached is checked below like any other.
  }
  const Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(x.data(), k);
  // A move within kPlateauStep is the level's own width about a single optimum: the minimax point stands.
  if ((u - minimax.u).cwiseAbs().maxCoeff() < kPlateauStep) return minimax;
  const double largest = problem.objective(u, CalibrationObjective::kMinimax);
  return largest <= level ? FitSolution{u, largest} : minimax;  // SLSQP may end a step outside the level
}

}  // namespace

int scanPoints(std::size_t keys) { return 41 + 32 * static_cast<int>(keys - 1); }

namespace {

// The local solve from one start: least squares by Ceres, a minimax by SLSQP.
FitSolution localSolve(const FitProblem& problem, CalibrationObjective objective, const Eigen::VectorXd& start,
                       double start_objective) {
  if (objective != CalibrationObjective::kMinimax) return leastSquaresFrom(problem, start, kIterations);
  FitSolution local = minimaxFrom(problem, start, start_objective);
  FitSolution best{start, start_objective};
  return local.objective < best.objective ? local : best;
}

}  // namespace

namespace {

// The best distinct points of @p scanned (objective, point), each solved locally; the best of all. With
// @p settle_plateau, a minimax fit then takes the least squares within its level (leastSquaresWithinLevel).
FitSolution fromTheBestOf(const FitProblem& problem, CalibrationObjective objective,
                          std::vector<std::pair<double, Eigen::VectorXd>> scanned, bool settle_plateau) {
  if (scanned.empty()) {
    throw ParameterError("no point of the keys' search range gives every row a shape (each is beyond the limit point "
                         "with no far branch): the start parameters or the data are far from this finger");
  }
  std::stable_sort(scanned.begin(), scanned.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<const std::pair<double, Eigen::VectorXd>*> starts;
  for (const auto& s : scanned) {
    const bool distinct = std::none_of(starts.begin(), starts.end(), [&](const auto* t) {
      return (t->second - s.second).cwiseAbs().maxCoeff() < kDistinct;
    });
    if (distinct) starts.push_back(&s);
    if (starts.size() == kStarts) break;
  }
  FitSolution best{scanned.front().second, scanned.front().first};
  std::vector<FitSolution> local(starts.size());
  onEveryCore(starts.size(), [&](std::size_t i) {
    local[i] = localSolve(problem, objective, starts[i]->second, starts[i]->first);
  });
  for (const FitSolution& l : local) {
    if (l.objective < best.objective) best = l;
  }
  // Then Subplex, which needs no derivative, from the best: where a key's step leaves the rows' shapes (its column is
  // zero) the derivative solvers cannot move it, and where the objective has kinks (a row that snaps between two
  // neighbouring points) their steps stall.
  const FitSolution polished = derivativeFreeFrom(problem, best.u, objective);
  if (polished.objective < best.objective) best = polished;
  if (objective == CalibrationObjective::kMinimax) {
    // Where the fit is (nearly) exact, minimax's optimum is degenerate (every term zero at once) and SLSQP's end game
    // slow: least squares from there, measured by the largest error, reaches it (Levenberg-Marquardt converges
    // quadratically on zero residuals, so a few iterations do; elsewhere it is a candidate that loses).
    const FitSolution squares = leastSquaresFrom(problem, best.u, kCandidateIterations);
    const double largest = problem.objective(squares.u, objective);
    if (largest < best.objective) best = {squares.u, largest};
    if (settle_plateau) best = leastSquaresWithinLevel(problem, best);
  }
  return best;
}

}  // namespace


FitSolution solveFit(const FitProblem& problem, CalibrationObjective objective, ScanRecord* record) {
  if (objective == CalibrationObjective::kHuber) {
    const CalibrationObjective squares = CalibrationObjective::kLeastSquares;
    return huberFrom(problem, fromTheBestOf(problem, squares, scan(problem, squares, record), false).u);
  }
  return fromTheBestOf(problem, objective, scan(problem, objective, record), true);
}

void scanInto(const FitProblem& problem, CalibrationObjective objective, ScanRecord& record) {
  scan(problem, objective == CalibrationObjective::kHuber ? CalibrationObjective::kLeastSquares : objective, &record);
}

FitSolution solveFold(const FitProblem& fold, CalibrationObjective objective, const ScanRecord& full,
                      std::size_t first_term, std::size_t terms) {
  std::vector<bool> kept(full.points.empty() ? 0 : static_cast<std::size_t>(full.points.front().second.size()), true);
  std::fill_n(kept.begin() + static_cast<long>(first_term), terms, false);
  return solveFold(fold, objective, full, kept);
}

FitSolution solveFold(const FitProblem& fold, CalibrationObjective objective, const ScanRecord& full,
                      const std::vector<bool>& kept_terms) {
  std::vector<std::pair<double, Eigen::VectorXd>> scanned;
  const bool huber = objective == CalibrationObjective::kHuber;  // its starts: the least-squares fit's
  const auto kept_count = static_cast<Eigen::Index>(std::count(kept_terms.begin(), kept_terms.end(), true));
  for (const auto& [u, e] : full.points) {
    Eigen::VectorXd others(kept_count);
    Eigen::Index j = 0;
    for (Eigen::Index t = 0; t < e.size(); ++t) {
      if (kept_terms[static_cast<std::size_t>(t)]) others[j++] = e[t];
    }
    scanned.emplace_back(reduce(others, huber ? CalibrationObjective::kLeastSquares : objective), u);
  }
  // A fold's fit predicts its rows; its place on a minimax plateau is no error bar's, and is not settled.
  if (huber) {
    return huberFrom(fold, fromTheBestOf(fold, CalibrationObjective::kLeastSquares, std::move(scanned), false).u);
  }
  return fromTheBestOf(fold, objective, std::move(scanned), false);
}

}  // namespace pneumatic_finger
