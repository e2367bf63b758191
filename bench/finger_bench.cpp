// finger_bench: speed against error for every way of evaluating the finger, side by side in one run.
//
// Each variant evaluates the whole finger (N = 7: stages 1-6, joint angles and backbone) at pressures that change
// on every call (so the unchanged-pressure cache never answers). Counters carry, from the same run, the largest
// error against the quad-precision reference: over the validated range (0..2 kg/cm^2) and over docs/MODEL.md's hard
// cases separately, where `hard_failures` counts pressures at which the variant returned no finite answer.
#include <benchmark/benchmark.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_poly.h>

#include <unsupported/Eigen/Polynomials>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/stages.hpp"
#include "reference_quad.hpp"
#include "../src/core/simd_math.hpp"  // the arctangent of our own (internal), for its latency
#include "../src/core/table_kernel.hpp"  // the table's polynomial variants (internal), per instruction set

namespace pf = pneumatic_finger;

namespace {

// The timed loop of a finger evaluation: @p evaluate on each input in turn, its backbone kept from the optimiser.
template <class Evaluate>
void timeEvaluations(benchmark::State& state, const std::vector<double>& inputs, Evaluate evaluate) {
  std::size_t i = 0;
  for (auto _ : state) {
    const pf::FingerState& s = evaluate(inputs[i]);
    benchmark::DoNotOptimize(s.backbone_m.data());
    benchmark::ClobberMemory();
    if (++i == inputs.size()) i = 0;
  }
}


const pf::FingerParameters kParams = pf::FingerParameters::defaults();

// A whole-finger evaluator: pressure in, state out.
struct Variant {
  virtual ~Variant() = default;
  virtual const pf::FingerState& evaluate(double gauge_pa) = 0;
};

struct ModelVariant : Variant {
  explicit ModelVariant(pf::SolverKind kind, bool detail) {
    pf::ModelOptions o;
    o.solver = kind;
    o.chamber_detail = detail;
    model = std::make_unique<pf::FingerModel>(kParams, o);
    workspace = std::make_unique<pf::FingerWorkspace>(*model);
  }
  const pf::FingerState& evaluate(double p) override { return model->evaluate(p, *workspace); }
  std::unique_ptr<pf::FingerModel> model;
  std::unique_ptr<pf::FingerWorkspace> workspace;
};

// What a user might write instead: the robust stages 1-3, then eq 16-22's quartic handed to a general polynomial
// root finder, the real root in [0, 1] that satisfies Wang's relation, theta = asin(y). Identical chambers are
// still solved once.
struct PolynomialVariant : Variant {
  using RootFinder = std::function<int(const double* coeffs_low_to_high, double* re, double* im)>;
  explicit PolynomialVariant(RootFinder f) : find(std::move(f)), state(pf::restState(kParams)),
                                             half(static_cast<std::size_t>(kParams.chamber_count)) {}
  const pf::FingerState& evaluate(double p) override {
    const double c = kParams.chamber_gap_m[0], b = kParams.wall_critical_height_m[0];
    const double g = pf::energyGroup(p, kParams.atmospheric_pressure_pa, kParams.shear_modulus_pa[0]);
    const double h = pf::bulge(pf::stretchExcess(g), kParams.chamber_height_m[0]);
    pf::HalfAngle a;
    if (h > c) {
      const auto q = pf::paper::quarticCoefficients(h, c, b);  // A y^4 + ... + E
      const double low_to_high[5] = {q[4], q[3], q[2], q[1], q[0]};
      double re[4], im[4];
      const int count = find(low_to_high, re, im);
      double best = std::numeric_limits<double>::quiet_NaN(), best_residual = 1e-6;
      for (int i = 0; i < count; ++i) {
        if (std::fabs(im[i]) > 1e-9 || !(re[i] >= 0 && re[i] <= 1)) continue;
        const double theta = std::asin(re[i]);
        const double residual = std::fabs(pf::bulgeForHalfAngle(theta, c, b) - h) / h;
        if (residual < best_residual) {
          best_residual = residual;
          best = theta;
        }
      }
      a.rad = best;
      a.cos = std::cos(best);
      a.sin = std::sin(best);
    }
    std::fill(half.begin(), half.end(), a);
    pf::jointsAndBackbone(kParams, half.data(), state);
    return state;
  }
  RootFinder find;
  pf::FingerState state;
  std::vector<pf::HalfAngle> half;
};

std::unique_ptr<Variant> eigenVariant() {
  auto solver = std::make_shared<Eigen::PolynomialSolver<double, 4>>();
  return std::make_unique<PolynomialVariant>([solver](const double* c, double* re, double* im) {
    Eigen::Matrix<double, 5, 1> coeffs;
    for (int i = 0; i < 5; ++i) coeffs[i] = c[i];
    solver->compute(coeffs);
    const auto& roots = solver->roots();
    for (int i = 0; i < 4; ++i) {
      re[i] = roots[i].real();
      im[i] = roots[i].imag();
    }
    return 4;
  });
}

std::unique_ptr<Variant> gslVariant() {
  gsl_set_error_handler_off();  // a failed solve is reported by its return code, not by abort()
  std::shared_ptr<gsl_poly_complex_workspace> w(gsl_poly_complex_workspace_alloc(5), gsl_poly_complex_workspace_free);
  return std::make_unique<PolynomialVariant>([w](const double* c, double* re, double* im) {
    double z[8];
    if (gsl_poly_complex_solve(c, 5, w.get(), z) != GSL_SUCCESS) return 0;
    for (int i = 0; i < 4; ++i) {
      re[i] = z[2 * i];
      im[i] = z[2 * i + 1];
    }
    return 4;
  });
}

std::unique_ptr<Variant> makeVariant(const std::string& name) {
  if (name == "robust") return std::make_unique<ModelVariant>(pf::SolverKind::kRobust, true);
  if (name == "paper") return std::make_unique<ModelVariant>(pf::SolverKind::kPaper, true);
  if (name == "table") return std::make_unique<ModelVariant>(pf::SolverKind::kTable, false);
  if (name == "eigen_companion") return eigenVariant();
  return gslVariant();
}

const std::vector<double>& validatedPressures() {
  static const std::vector<double> p = [] {
    std::vector<double> v;
    for (int i = 0; i < 1024; ++i) v.push_back(196133.0 * (i + 0.5) / 1024);  // 0..2 kg/cm^2
    return v;
  }();
  return p;
}

// docs/MODEL.md's hard cases, as pressures on the default actuator.
const std::vector<double>& hardPressures() {
  static const std::vector<double> p = [] {
    std::vector<double> v;
    for (double x = 1e-9; x < 10; x *= 10) v.push_back(x);  // near rest
    const double pc = pf::contactGaugePa(kParams.chamber_height_m[0], kParams.chamber_gap_m[0],
                                         kParams.shear_modulus_pa[0], kParams.atmospheric_pressure_pa);
    for (int k = 1; k <= 15; ++k) {
      v.push_back(pc * (1 - std::pow(10.0, -k)));
      v.push_back(pc * (1 + std::pow(10.0, -k)));
    }
    for (double e = 7.5; e <= 9.0; e += 0.1) v.push_back(std::pow(10.0, e));  // resolvent branch band
    for (double x : {1e10, 1e12, 1e15, 1e50, 1e100, 1e300}) v.push_back(x);  // theta -> pi/2
    return v;
  }();
  return p;
}

struct Errors {
  double theta = 0, tip = 0;
  int failures = 0;
};

Errors measureErrors(Variant& v, const std::vector<double>& pressures) {
  Errors e;
  for (double p : pressures) {
    std::vector<reference::ChamberGeometry> chambers(static_cast<std::size_t>(kParams.chamber_count),
                                                     {kParams.chamber_height_m[0], kParams.wall_critical_height_m[0],
                                                      kParams.chamber_gap_m[0], kParams.shear_modulus_pa[0]});
    const reference::Finger ref = reference::finger(p, kParams.atmospheric_pressure_pa, chambers,
                                                    kParams.segment_length_m, kParams.base_segment_length_m,
                                                    kParams.base_wall_share);
    const pf::FingerState& s = v.evaluate(p);
    const Eigen::Vector2d tip = s.tip();
    const double dt = std::fabs(s.half_angle_rad[0] - ref.half_angle_rad[0]);
    const double dx = std::hypot(tip.x() - ref.x_m.back(), tip.y() - ref.y_m.back());
    if (s.status == pf::EvaluationStatus::kSolverFailure || !std::isfinite(dt) || !std::isfinite(dx)) {
      ++e.failures;
      continue;
    }
    e.theta = std::max(e.theta, dt);
    e.tip = std::max(e.tip, dx);
  }
  return e;
}

// Google Benchmark calls a benchmark function several times (to size its iterations); the reference is
// computed once per variant and case set.
const Errors& cachedErrors(const std::string& name, bool hard, Variant& v, const std::vector<double>& pressures) {
  static std::map<std::pair<std::string, bool>, Errors> cache;
  const auto key = std::make_pair(name, hard);
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, measureErrors(v, pressures)).first;
  return it->second;
}

void benchVariant(benchmark::State& state, const std::string& name, bool hard) {
  const std::vector<double>& pressures = hard ? hardPressures() : validatedPressures();
  auto variant = makeVariant(name);
  const Errors err = cachedErrors(name, hard, *variant, pressures);
  timeEvaluations(state, pressures, [&](double p) -> const pf::FingerState& { return variant->evaluate(p); });
  state.counters["max_theta_error_rad"] = err.theta;
  state.counters["max_tip_error_m"] = err.tip;
  state.counters["failures"] = err.failures;
  state.counters["pressures"] = static_cast<double>(pressures.size());
  state.SetLabel(hard ? "hard cases" : "validated range");
}

// The paper's finger with a silicone wall under @p law: mu = 20 kPa, t = 2 mm, Gent J_m = 50 (so a limit point).
pf::FingerParameters siliconeFinger(pf::WallLaw law) {
  pf::FingerParameters params = kParams;
  params.wall_law = law;
  params.shear_modulus_pa.assign(params.shear_modulus_pa.size(), 2e4);
  params.wall_thickness_m.assign(params.wall_thickness_m.size(), 0.002);
  params.wall_locking_jm = 50.0;
  return params;
}

// The membrane wall law (docs/MODEL.md): the paper's finger with a silicone wall (mu = 20 kPa, t = 2 mm, Gent
// J_m = 50, so a limit point), 64 pressures from rest to 0.99 of the limit point, one at a time as the node runs
// them; under the membrane law its error against the quad reference (the law by bisection, Wang's half angle by
// bisection) as a counter. @p law: the membrane or the thick wall (the same finger, its wall's real thickness).
// @p wall_inverse: the wall's inverse (docs/MODEL.md, "The wall's inverse"), or the Newton steps without it.
void benchMembrane(benchmark::State& state, pf::WallLaw law, bool wall_inverse) {
  const pf::FingerParameters params = siliconeFinger(law);
  pf::ModelOptions options;
  options.wall_inverse = wall_inverse;
  const pf::FingerModel model(params, options);
  pf::FingerWorkspace ws(model);
  std::vector<double> pressures;
  for (int i = 1; i <= 64; ++i) pressures.push_back(0.99 * model.limitGaugePa() * i / 64.0);
  if (law == pf::WallLaw::kMembrane) {
    double worst = 0.0;
    const reference::Membrane wall{2e4, 0.002, params.chamber_height_m[0], 50.0};
    for (double p : pressures) {
      const double h = 0.5 * params.chamber_height_m[0] * reference::membraneStretchExcess(wall, p);
      const double theta = reference::halfAngleForBulge(h, params.chamber_gap_m[0], params.wall_critical_height_m[0]);
      worst = std::max(worst, std::fabs(model.evaluate(p, ws).half_angle_rad[0] - theta));
    }
    state.counters["max_theta_error_rad"] = worst;
  }
  timeEvaluations(state, pressures, [&](double p) -> const pf::FingerState& { return model.evaluate(p, ws); });
  state.SetLabel(std::string(pf::wallLawName(law)) + " wall law, Gent, up to 0.99 of the limit point, " +
                 (wall_inverse ? "the wall's inverse" : "Newton steps"));
}

// Building membrane/validated's model (FingerModel's constructor: the wall, its limit point and turning points, the
// force and volume models) with and without the wall's inverse: what the inverse costs a model once.
void benchMembraneBuild(benchmark::State& state, pf::WallLaw law, bool wall_inverse) {
  const pf::FingerParameters params = siliconeFinger(law);
  pf::ModelOptions options;
  options.wall_inverse = wall_inverse;
  for (auto _ : state) {
    const pf::FingerModel model(params, options);
    benchmark::DoNotOptimize(model.limitGaugePa());
  }
  state.SetLabel(std::string(pf::wallLawName(law)) + " wall law, Gent, FingerModel built " +
                 (wall_inverse ? "with the wall's inverse" : "without it"));
}

// The membrane and thick wall laws through the batch (evaluateMany): membrane/validated's finger and range, 4096
// pressures in order from rest to 0.99 of the limit point, every output, one at a time (scalar) or in packs: the time
// per pressure (the time over the counter pressures) sets beside membrane/validated and thick/validated.
void benchMembraneBatch(benchmark::State& state, pf::WallLaw law, pf::BatchPath path) {
  if (!pf::batchPathAvailable(path)) {
    state.SkipWithError("this CPU lacks the instruction set");
    return;
  }
  const pf::FingerParameters params = siliconeFinger(law);
  const pf::FingerModel model(params);
  pf::FingerWorkspace ws(model);
  constexpr std::size_t kCount = 4096;
  std::vector<double> pressures;
  for (std::size_t i = 1; i <= kCount; ++i) pressures.push_back(0.99 * model.limitGaugePa() * i / kCount);
  pf::BatchBuffers rows(kCount, params.chamber_count);
  for (auto _ : state) {
    model.evaluateMany(pressures.data(), kCount, rows.outputs(), ws, path);
    benchmark::DoNotOptimize(rows.backbone_m.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(kCount));
  state.counters["pressures"] = static_cast<double>(kCount);
  state.SetLabel(std::string(pf::wallLawName(law)) + " wall law, Gent, evaluateMany, " + pf::batchPathName(path));
}

// Volume as the input (docs/MODEL.md, "Volume"): @p model at the volumes it takes at 64 pressures up to @p top_pa,
// one at a time, with the largest relative error in the pressure each volume gives back as a counter.
void benchVolumeInput(benchmark::State& state, const pf::FingerModel& model, double top_pa, const std::string& label) {
  pf::FingerWorkspace ws(model);
  std::vector<double> volumes;
  double worst = 0.0;
  for (int i = 1; i <= 64; ++i) {
    const double p = top_pa * i / 64.0;
    volumes.push_back(model.suppliedVolumeAt(p));
    worst = std::max(worst, std::fabs(model.evaluateVolume(volumes.back(), ws).gauge_pa - p) / p);
  }
  timeEvaluations(state, volumes, [&](double v) -> const pf::FingerState& { return model.evaluateVolume(v, ws); });
  state.counters["max_gauge_relative_error"] = worst;
  state.SetLabel(label);
}

// Beside membrane/validated: the same finger with 10 mL of gas in the drive, up to 0.99 of its limit point.
void benchMembraneVolume(benchmark::State& state) {
  pf::FingerParameters params = siliconeFinger(pf::WallLaw::kMembrane);
  params.dead_volume_m3 = 1e-5;
  const pf::FingerModel model(params);
  benchVolumeInput(state, model, 0.99 * model.limitGaugePa(),
                   "membrane wall law, Gent, volume input, the volumes of membrane/validated's pressures");
}

// Beside robust/validated: the package's paper-law finger with an incompressible drive, over the validated range
// (by bisection on the pressure before; now the closed form: the bulge from the volume and the law's inverse).
void benchPaperVolume(benchmark::State& state) {
  const pf::FingerModel model(pf::FingerParameters::defaults());
  benchVolumeInput(state, model, pf::kValidatedMaxGaugePa,
                   "paper wall law, volume input (incompressible), the volumes of 64 pressures up to 196133 Pa");
}

// The blocked tip force (docs/MODEL.md, "Force") at the pressures robust/validated runs, beside the shape it adds to:
// its cost is one wall solve (stages 1-3) and a strip's square root. Its largest relative error, over the pressures
// past twice the contact pressure, against the quad reference's bulge through the page's formula, as a counter.
void benchBlockedForce(benchmark::State& state) {
  const std::vector<double>& pressures = validatedPressures();
  const pf::FingerModel model(kParams);
  const reference::ChamberGeometry chamber{kParams.chamber_height_m[0], kParams.wall_critical_height_m[0],
                                           kParams.chamber_gap_m[0], kParams.shear_modulus_pa[0]};
  long double l = 0, lw = 0, l2w = 0;
  for (int j = kParams.chamber_count - 1; j >= 0; --j) {
    l += kParams.segment_length_m[static_cast<std::size_t>(j)];
    const long double w = j == 0 ? 1 + kParams.base_wall_share : 2;
    lw += l * w;
    l2w += l * l * w;
  }
  double worst = 0.0;
  for (double p : pressures) {
    if (p < 2 * model.contactGaugePa()) continue;
    const long double r = 0.5L * kParams.chamber_height_m[0], c = kParams.chamber_gap_m[0];
    const long double h = reference::chamberChain(p, kParams.atmospheric_pressure_pa, chamber).bulge_m;
    const long double strip = 2 * r / (r + h) * std::sqrt((r + h) * (r + h) - (r + c) * (r + c));
    const long double f = p * strip * kParams.chamber_width_m[0] * kParams.wall_critical_height_m[0] * lw / l2w;
    worst = std::max(worst, static_cast<double>(std::fabs(model.blockedTipForceN(p) - f) / f));
  }
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(model.blockedTipForceN(pressures[i]));
    if (++i == pressures.size()) i = 0;
  }
  state.counters["max_relative_error"] = worst;
  state.SetLabel("blocked tip force, validated range");
}

// The normal forces at the contacts (contactNormalForcesN) of the disk of contact/2, on the tracker's states at the
// validated pressures: what a grasp adds to its contact solve when someone asks for the force. The states are solved
// beforehand; only the force is timed.
void benchContactForce(benchmark::State& state) {
  const std::vector<double>& pressures = validatedPressures();
  const pf::FingerModel model(kParams);
  pf::ContactTracker tracker(model, pf::Obstacle::disk(0.075, 0.035, 0.01));
  std::vector<pf::ContactState> states;
  std::vector<double> touching;
  for (double p : pressures) {
    pf::ContactState s = tracker.solve(p);
    if (s.status != pf::ContactState::Status::kInContact) continue;
    states.push_back(std::move(s));
    touching.push_back(p);
  }
  std::vector<double> force;
  std::size_t i = 0;
  for (auto _ : state) {
    pf::contactNormalForcesN(model, touching[i], states[i], force);
    benchmark::DoNotOptimize(force.data());
    if (++i == states.size()) i = 0;
  }
  state.counters["pressures"] = static_cast<double>(states.size());
  state.SetLabel("contact normal forces, disk at the tip, touching pressures");
}

// Two independent models (robust solver) evaluated alternately, each on its own pressure: if the CPU overlapped one
// evaluation with the next, a pair would take less than twice one evaluation (robust/validated, the same loop).
void benchPair(benchmark::State& state) {
  const std::vector<double>& pressures = validatedPressures();
  auto first = makeVariant("robust"), second = makeVariant("robust");
  std::size_t i = 0;
  for (auto _ : state) {
    const pf::FingerState& a = first->evaluate(pressures[i]);
    const pf::FingerState& b = second->evaluate(pressures[i + 1]);
    benchmark::DoNotOptimize(a.backbone_m.data());
    benchmark::DoNotOptimize(b.backbone_m.data());
    benchmark::ClobberMemory();
    i += 2;
    if (i + 1 >= pressures.size()) i = 0;
  }
  state.counters["evaluations_per_iteration"] = 2;
  state.SetLabel("two independent models, alternately");
}

// The pieces of an evaluation alone, over the validated range, to show where its time goes: one wall's chain as the
// robust solver runs it (solveWall: stages 1-3 by their series in s, then stage 4), stage 4 alone from the bulge, the
// whole finger's half angles without writing a state (tipAngleAt: one solve and a sum) for the robust and the table
// solvers, and the joints and backbone of the general path (unequal chambers) from given half angles.
void benchStages(benchmark::State& state, int stage) {
  const std::vector<double>& pressures = validatedPressures();
  const double p_o = kParams.atmospheric_pressure_pa, mu = kParams.shear_modulus_pa[0];
  const double l = kParams.chamber_height_m[0], b = kParams.wall_critical_height_m[0], c = kParams.chamber_gap_m[0];
  std::vector<double> h(pressures.size());
  std::vector<pf::HalfAngle> theta(pressures.size());
  for (std::size_t i = 0; i < pressures.size(); ++i) {
    const pf::WallSolution w = pf::solveWall(pressures[i], p_o, mu, l, c, b);
    h[i] = w.bulge_m;
    theta[i] = w.half;
  }
  pf::ModelOptions table_options;
  table_options.solver = pf::SolverKind::kTable;
  const pf::FingerModel robust(kParams), table(kParams, table_options);
  pf::FingerState out = pf::restState(kParams);
  std::vector<pf::HalfAngle> seven(7);
  std::size_t i = 0;
  for (auto _ : state) {
    switch (stage) {
      case 1: benchmark::DoNotOptimize(pf::solveWall(pressures[i], p_o, mu, l, c, b)); break;
      case 2: benchmark::DoNotOptimize(pf::halfAngle(h[i], c, b)); break;
      case 3: benchmark::DoNotOptimize(robust.tipAngleAt(pressures[i])); break;
      case 4: benchmark::DoNotOptimize(table.tipAngleAt(pressures[i])); break;
      default:
        std::fill(seven.begin(), seven.end(), theta[i]);
        pf::jointsAndBackbone(kParams, seven.data(), out);
        benchmark::DoNotOptimize(out.backbone_m.data());
    }
    if (++i == pressures.size()) i = 0;
  }
  static const char* const kLabels[] = {"", "one wall, stages 1-4 (solveWall)", "stage 4 alone, theta(h)",
                                       "robust: the tip angle only, no state written (tipAngleAt)",
                                       "table: the tip angle only, no state written (tipAngleAt)",
                                       "joints + backbone (N = 7, general path)"};
  state.SetLabel(kLabels[stage]);
}

// The table solver's polynomials alone (table_kernel.hpp), per instruction set: what evaluate() runs for a finger of
// identical chambers after the segment lookup. N = 7: 16 functions (theta, 14 point coordinates and a zero; 15
// stored), 8 coefficients each, over as many segments as the calibrated finger's table has, at x values that change
// every call.
void benchTablePolynomials(benchmark::State& state, void (*polynomials)(const double*, int, int, double, double*),
                           const char* label) {
  pf::ModelOptions table_options;
  table_options.solver = pf::SolverKind::kTable;
  const int segments = pf::FingerModel(kParams, table_options).tableSegmentCount();
  constexpr int kFunctions = 16, kLive = 15;  // theta and 14 point coordinates, padded to 16
  std::vector<double> table(static_cast<std::size_t>(segments) * 8 * kFunctions);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
  for (double& c : table) c = coefficient(rng);
  alignas(64) double out[kFunctions];
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t segment = i % static_cast<std::size_t>(segments);
    const double x = -1.0 + 2.0 * static_cast<double>(i % 1000) / 1000.0;
    polynomials(&table[segment * 8 * kFunctions], kFunctions, kLive, x, out);
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
    ++i;
  }
  state.counters["segments"] = segments;
  state.counters["table_bytes"] = static_cast<double>(table.size() * sizeof(double));
  state.SetLabel(label);
}

// Latency of the primitives the solvers chain together: each result feeds the next call, so this is the
// dependent-chain latency that bounds a full evaluation, not the throughput.
void benchPrimitive(benchmark::State& state, int which) {
  double x = 0.3;
  for (auto _ : state) {
    switch (which) {
      case 0: x = std::sqrt(x) + 0.3; break;
      case 1: x = 1.0 / (x + 0.7); break;
      case 2: x = std::atan(x) + 0.3; break;
      default: x = pf::atanNonNegative(x) + 0.3;
    }
    benchmark::DoNotOptimize(x);
  }
  state.SetLabel(which == 0 ? "sqrt" : which == 1 ? "division" : which == 2 ? "atan (glibc)" : "atan (ours)");
}

// The contact rule's cost beside the free finger's (robust solver, validated range): an obstacle out of reach (the
// reach test only), and a disk the tip reaches (bracketing and bisection for one touch at the higher pressures).
void benchContact(benchmark::State& state, int which) {
  const std::vector<double>& pressures = validatedPressures();
  // which == 3: from scratch on a finger whose base face is inert (base_wall_share = 0): the half-angle search then
  // needs one sincos per sample, not two (joint 1 turns by theta itself).
  pf::FingerParameters params = kParams;
  if (which == 3) params.base_wall_share = 0.0;
  // which == 4: from scratch on a finger whose chambers differ (one gap 1 % wider): the search then runs in sqrt(P),
  // a model solve per sample.
  if (which == 4) params.chamber_gap_m.back() *= 1.01;
  pf::FingerModel model(params);
  const pf::ContactSolver solver(model);
  const pf::Obstacle obstacle = which == 0 ? pf::Obstacle::disk(0.0, 0.2, 0.01) : pf::Obstacle::disk(0.075, 0.035, 0.01);
  // which == 2: a ContactTracker on the same disk (a grasp: the object stays, the pressure changes).
  pf::ContactTracker tracker(model, obstacle);
  std::size_t i = 0;
  for (auto _ : state) {
    const pf::ContactState s = which == 2 ? tracker.solve(pressures[i]) : solver.solve(pressures[i], obstacle);
    benchmark::DoNotOptimize(s.backbone_m.data());
    if (++i == pressures.size()) i = 0;
  }
  static const char* const kLabels[] = {"contact: obstacle out of reach",
                                       "contact: disk at the tip, one touch, from scratch",
                                       "contact: the same, ContactTracker (events kept)",
                                       "contact: from scratch, inert base face (base_wall_share = 0)",
                                       "contact: from scratch, unequal chambers (search in sqrt(P))"};
  state.SetLabel(kLabels[which]);
}

// The batch entry point (FingerModel::evaluateMany) over the validated pressures, every output written to arrays the
// caller owns: the one-at-a-time path and the SIMD packs side by side, with the error of what they wrote (the tests
// check that every path writes the bits of evaluate(); the error is measured here anyway, from the batch's rows).
void benchBatch(benchmark::State& state, pf::BatchPath path, bool backbone_only) {
  if (!pf::batchPathAvailable(path)) {
    state.SkipWithError("this CPU lacks the instruction set");
    return;
  }
  const std::vector<double>& pressures = validatedPressures();
  const std::size_t count = pressures.size();
  const auto n = static_cast<std::size_t>(kParams.chamber_count);
  pf::BatchBuffers rows(count, kParams.chamber_count);
  pf::BatchOutputs out = rows.outputs();
  if (backbone_only) out = pf::BatchOutputs{nullptr, nullptr, nullptr, nullptr, rows.backbone_m.data(), nullptr, nullptr};
  const pf::FingerModel model(kParams);
  pf::FingerWorkspace workspace(model);
  for (auto _ : state) {
    model.evaluateMany(pressures.data(), count, out, workspace, path);
    benchmark::DoNotOptimize(rows.backbone_m.data());
    benchmark::ClobberMemory();
  }
  double theta_error = 0.0, tip_error = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    std::vector<reference::ChamberGeometry> chambers(n, {kParams.chamber_height_m[0], kParams.wall_critical_height_m[0],
                                                         kParams.chamber_gap_m[0], kParams.shear_modulus_pa[0]});
    const reference::Finger ref = reference::finger(pressures[i], kParams.atmospheric_pressure_pa, chambers,
                                                    kParams.segment_length_m, kParams.base_segment_length_m,
                                                    kParams.base_wall_share);
    theta_error = std::max(theta_error, std::fabs(rows.half_angle_rad[i * n] - ref.half_angle_rad[0]));
    const double* o = &rows.backbone_m[i * 2 * (n + 2) + 2 * (n + 1)];
    tip_error = std::max(tip_error, std::hypot(o[0] - ref.x_m.back(), o[1] - ref.y_m.back()));
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(count));
  state.counters["max_theta_error_rad"] = theta_error;
  state.counters["max_tip_error_m"] = tip_error;
  state.counters["pressures"] = static_cast<double>(count);
  state.SetLabel(std::string("evaluateMany, ") + pf::batchPathName(path) +
                 (backbone_only ? ", backbone only" : ", every output"));
}

// The batch as a Python sweep uses it (scripts/bench_python.py times the same calls from Python in the same run of
// scripts/benchmarks.py): 2 million pressures, uniform over the validated range, into arrays allocated (and touched)
// once; the tip angle alone (the kernel leaves the backbone out), or every output.
void benchBatchSweep(benchmark::State& state, bool tip_only) {
  constexpr std::size_t kCount = 2000000;
  std::vector<double> pressures(kCount);
  std::mt19937_64 random(2);
  std::uniform_real_distribution<double> uniform(0.0, pf::kValidatedMaxGaugePa);
  for (double& p : pressures) p = uniform(random);
  pf::BatchBuffers rows(kCount, kParams.chamber_count);
  pf::BatchOutputs out = rows.outputs();
  if (tip_only) out = pf::BatchOutputs{nullptr, nullptr, nullptr, nullptr, nullptr, rows.tip_angle_rad.data(), nullptr};
  const pf::FingerModel model(kParams);
  pf::FingerWorkspace workspace(model);
  for (auto _ : state) {
    model.evaluateMany(pressures.data(), kCount, out, workspace);
    benchmark::DoNotOptimize(rows.tip_angle_rad.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(kCount));
  state.counters["pressures"] = static_cast<double>(kCount);
  state.SetLabel(tip_only ? "C++ evaluateMany, 2 M pressures, tip angle only" : "C++ evaluateMany, 2 M pressures, every output");
}

}  // namespace

int main(int argc, char** argv) {
  for (const char* name : {"robust", "table", "paper", "eigen_companion", "gsl_complex"}) {
    for (bool hard : {false, true}) {
      benchmark::RegisterBenchmark((std::string(name) + (hard ? "/hard" : "/validated")).c_str(),
                                   [name, hard](benchmark::State& s) { benchVariant(s, name, hard); });
    }
  }
  benchmark::RegisterBenchmark("robust_pair/validated", benchPair);
  benchmark::RegisterBenchmark("force/blocked_tip", benchBlockedForce);
  benchmark::RegisterBenchmark("force/contact", benchContactForce);
  for (pf::WallLaw law : {pf::WallLaw::kMembrane, pf::WallLaw::kThick}) {
    const std::string name = pf::wallLawName(law);
    benchmark::RegisterBenchmark((name + "/validated").c_str(), benchMembrane, law, true);
    benchmark::RegisterBenchmark((name + "/newton").c_str(), benchMembrane, law, false);
    benchmark::RegisterBenchmark((name + "/build").c_str(), benchMembraneBuild, law, true);
    benchmark::RegisterBenchmark((name + "/build_newton").c_str(), benchMembraneBuild, law, false);
  }
  benchmark::RegisterBenchmark("membrane/volume", benchMembraneVolume);
  benchmark::RegisterBenchmark("paper/volume", benchPaperVolume);
  for (pf::WallLaw law : {pf::WallLaw::kMembrane, pf::WallLaw::kThick}) {
    for (pf::BatchPath path : {pf::BatchPath::kScalar, pf::BatchPath::kGeneric, pf::BatchPath::kAvx2,
                               pf::BatchPath::kAvx512}) {
      benchmark::RegisterBenchmark((std::string(pf::wallLawName(law)) + "_batch/" + pf::batchPathName(path)).c_str(),
                                   benchMembraneBatch, law, path);
    }
  }
  for (int stage = 1; stage <= 5; ++stage) {
    benchmark::RegisterBenchmark(("robust_stage/" + std::to_string(stage)).c_str(),
                                 [stage](benchmark::State& s) { benchStages(s, stage); });
  }
  struct TableVariant {
    const char* name;
    pf::InstructionSet set;
    const char* label;
  };
  for (const TableVariant& v : std::vector<TableVariant>{
           {"generic", pf::InstructionSet::kGeneric, "pairs, baseline instruction set (SSE2)"},
           {"avx2", pf::InstructionSet::kAvx2, "packs of 4, AVX2"},
           {"avx512", pf::InstructionSet::kAvx512, "packs of 8, AVX-512"},
       }) {
    const pf::SimdKernels* kernels = pf::simdKernels(v.set);
    if (!kernels) continue;  // this CPU lacks it
    const pf::TablePolynomials polynomials = kernels->table_polynomials;
    benchmark::RegisterBenchmark((std::string("table_polynomials/") + v.name).c_str(),
                                 [v, polynomials](benchmark::State& s) {
                                   benchTablePolynomials(s, polynomials, v.label);
                                 });
  }
  for (int which = 0; which < 4; ++which) {
    benchmark::RegisterBenchmark(("latency/" + std::to_string(which)).c_str(),
                                 [which](benchmark::State& s) { benchPrimitive(s, which); });
  }
  for (int which = 0; which < 5; ++which) {
    benchmark::RegisterBenchmark(("contact/" + std::to_string(which)).c_str(),
                                 [which](benchmark::State& s) { benchContact(s, which); });
  }
  for (pf::BatchPath path : {pf::BatchPath::kScalar, pf::BatchPath::kGeneric, pf::BatchPath::kAvx2,
                             pf::BatchPath::kAvx512}) {
    for (bool backbone_only : {false, true}) {
      benchmark::RegisterBenchmark(
          (std::string(backbone_only ? "batch_backbone/" : "batch/") + pf::batchPathName(path)).c_str(),
          [path, backbone_only](benchmark::State& s) { benchBatch(s, path, backbone_only); });
    }
  }
  for (bool tip_only : {true, false}) {
    benchmark::RegisterBenchmark(tip_only ? "batch_sweep/tip" : "batch_sweep/full",
                                 [tip_only](benchmark::State& s) { benchBatchSweep(s, tip_only); })
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
