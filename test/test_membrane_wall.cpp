// The membrane wall law (docs/MODEL.md, "The membrane law") against the quad-precision reference
// (test/reference_quad.cpp: the law written literally, its limit point from the literal derivative, bisection), and the
// limit point's status everywhere the model goes: evaluate, the batch, the free angles, the contact rule, the inverse.
#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/membrane_wall.hpp"
#include "pneumatic_finger/core/obstacle.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "reference_quad.hpp"
#include "test_support.hpp"

namespace pf = pneumatic_finger;

namespace {

// Three walls of a silicone finger (mu = 20 kPa, t = 2 mm, L = 11.5 mm): Neo-Hookean (a limit point), Gent with a
// late lock (a limit point, then the lock), Gent with an early lock (no limit point: P rises to the lock).
struct Case {
  const char* name;
  double locking_jm;
  bool has_limit;
};
const Case kCases[] = {{"neo_hookean", 0.0, true}, {"gent_jm_50", 50.0, true}, {"gent_jm_6", 6.0, false}};
constexpr double kMu = 2e4, kThickness = 0.002, kHeight = 0.0115;

reference::Membrane referenceWall(double jm) { return {kMu, kThickness, kHeight, jm}; }
pf::MembraneWall wall(double jm) { return pf::membraneWall(kMu, kThickness, kHeight, jm); }

using pf_test::membraneFinger;

// The top of a sweep: just below the limit point, or where the Gent wall is near its lock.
double sweepTop(const pf::MembraneWall& w) {
  return std::isfinite(w.limit_gauge_pa) ? w.limit_gauge_pa * (1 - 1e-6)
                                         : pf::membraneGaugeForStretchExcess(w, 0.999 * w.locking_stretch_excess);
}

}  // namespace

TEST(MembraneWall, LimitPointMatchesTheQuadReference) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.name);
    const pf::MembraneWall w = wall(c.locking_jm);
    const double ref_delta = reference::membraneLimitStretchExcess(referenceWall(c.locking_jm));
    ASSERT_EQ(std::isfinite(w.limit_gauge_pa), c.has_limit);
    if (!c.has_limit) {
      EXPECT_FALSE(ref_delta < 1e29) << "the reference finds a maximum at delta = " << ref_delta;
      continue;
    }
    EXPECT_NEAR(w.limit_stretch_excess, ref_delta, 1e-12 * ref_delta);
    const double ref_p = reference::membraneLimitGaugePa(referenceWall(c.locking_jm));
    EXPECT_NEAR(w.limit_gauge_pa, ref_p, 1e-15 * ref_p);
  }
  // Neo-Hookean: lambda^6 = 7 exactly.
  EXPECT_NEAR(wall(0).limit_stretch_excess, std::pow(7.0, 1.0 / 6.0) - 1.0, 1e-15);
}

// delta and Wang's half angle at 401 pressures from 1e-12 of the sweep's top to the top, against the reference.
void expectDenseSweepWithin1e12(const pf::MembraneWall& w, double locking_jm) {
  const double top = sweepTop(w);
  double worst_delta = 0, worst_theta = 0;
  for (int i = 0; i <= 400; ++i) {
    const double p = top * std::pow(10.0, -12.0 * (1.0 - i / 400.0));
    const double d = pf::membraneStretchExcess(w, p);
    const double d_ref = reference::membraneStretchExcess(referenceWall(locking_jm), p);
    worst_delta = std::max(worst_delta, std::fabs(d - d_ref) / d_ref);
    const pf::WallSolution s = pf::solveMembraneWall(w, p, 4e-5, 0.00575);
    const double theta_ref = reference::halfAngleForBulge(0.5 * kHeight * d_ref, 4e-5, 0.00575);
    worst_theta = std::max(worst_theta, std::fabs(s.half.rad - theta_ref));
  }
  EXPECT_LE(worst_delta, 1e-12);
  EXPECT_LE(worst_theta, 1e-12);
}

TEST(MembraneWall, DenseSweepWithin1e12OfTheQuadReference) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.name);
    expectDenseSweepWithin1e12(wall(c.locking_jm), c.locking_jm);
  }
}

// Eight ulp: the double law P(delta) (a polynomial, a power and a quotient) rounds about six times, and the solve can
// do no better than the P it inverts.
constexpr double kEightUlp = 8 * 2.220446049250313e-16;

// Near rest P = 6 (4 mu t/L) delta: delta keeps its digits down to the smallest pressures.
TEST(MembraneWall, NearRestKeepsItsDigits) {
  const pf::MembraneWall w = wall(0);
  for (double p : {1e-300, 1e-30, 1e-10, 1e-3}) {
    const double d = pf::membraneStretchExcess(w, p);
    const double d_ref = reference::membraneStretchExcess(referenceWall(0), p);
    EXPECT_NEAR(d, d_ref, kEightUlp * d_ref) << "P = " << p;
  }
  EXPECT_EQ(pf::membraneStretchExcess(w, 0.0), 0.0);
}

// Next to the limit point dP/d delta -> 0, so delta is ill-conditioned in P; what the solve owes is a delta on the
// rising branch whose pressure is the one asked for, to the rounding of P itself.
TEST(MembraneWall, NearTheLimitPointTheBackwardErrorIsAnUlp) {
  for (const Case& c : kCases) {
    if (!c.has_limit) continue;
    SCOPED_TRACE(c.name);
    const pf::MembraneWall w = wall(c.locking_jm);
    for (double gap : {1e-6, 1e-9, 1e-12, 1e-15}) {
      const double p = w.limit_gauge_pa * (1 - gap);
      const double d = pf::membraneStretchExcess(w, p);
      ASSERT_TRUE(std::isfinite(d)) << "gap " << gap;
      EXPECT_LE(d, w.limit_stretch_excess);
      EXPECT_NEAR(reference::membraneGaugePa(referenceWall(c.locking_jm), d), p, kEightUlp * p) << "gap " << gap;
    }
  }
}

// The wall's inverse (docs/MODEL.md, "The wall's inverse"), built as a model builds it, answers what the Newton steps
// answer above: the dense sweep, the digits near rest, the backward error next to the limit point. A Gent wall whose
// limit point and far turning point nearly meet (J_m = 19, just above the threshold where the limit point appears)
// joins the three: its inverse needs the most pieces.
TEST(MembraneWall, TheInverseAnswersAsTheNewtonStepsDo) {
  std::vector<Case> cases(std::begin(kCases), std::end(kCases));
  cases.push_back({"gent_jm_19", 19.0, true});
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    pf::MembraneWall w = wall(c.locking_jm);
    ASSERT_EQ(std::isfinite(w.limit_gauge_pa), c.has_limit);
    pf::buildRisingInverse(w);
    ASSERT_GT(w.inverse_pieces, 0);
    EXPECT_EQ(w.inverse_top_gauge_pa, c.has_limit ? w.limit_gauge_pa
                                                   : pf::membraneGaugeForStretchExcess(w, 0.8 * w.locking_stretch_excess));
    expectDenseSweepWithin1e12(w, c.locking_jm);
    for (double p : {1e-300, 1e-30, 1e-10, 1e-3}) {
      const double d_ref = reference::membraneStretchExcess(referenceWall(c.locking_jm), p);
      EXPECT_NEAR(pf::membraneStretchExcess(w, p), d_ref, kEightUlp * d_ref) << "P = " << p;
    }
    EXPECT_EQ(pf::membraneStretchExcess(w, 0.0), 0.0);
    if (!c.has_limit) continue;
    for (double gap : {1e-6, 1e-9, 1e-12, 1e-15}) {
      const double p = w.limit_gauge_pa * (1 - gap);
      const double d = pf::membraneStretchExcess(w, p);
      EXPECT_LE(d, w.limit_stretch_excess) << "gap " << gap;
      EXPECT_NEAR(reference::membraneGaugePa(referenceWall(c.locking_jm), d), p, kEightUlp * p) << "gap " << gap;
    }
    EXPECT_TRUE(std::isnan(pf::membraneStretchExcess(w, w.limit_gauge_pa)));
  }
}

TEST(MembraneWall, AtAndBeyondTheLimitPointThereIsNoStretch) {
  const pf::MembraneWall w = wall(0);
  for (double p : {w.limit_gauge_pa, std::nextafter(w.limit_gauge_pa, 1e300), 2 * w.limit_gauge_pa, 1e300}) {
    EXPECT_TRUE(std::isnan(pf::membraneStretchExcess(w, p))) << p;
    EXPECT_TRUE(std::isnan(pf::solveMembraneWall(w, p, 4e-5, 0.00575).half.rad)) << p;
  }
  EXPECT_TRUE(std::isnan(pf::membraneStretchExcess(w, -1.0)));
  EXPECT_TRUE(std::isnan(pf::membraneStretchExcess(w, std::nan(""))));
}

TEST(MembraneModel, BeyondTheLimitPointKeepsThePreviousStateWithItsOwnStatus) {
  const pf::FingerModel model(membraneFinger(0));
  ASSERT_TRUE(std::isfinite(model.limitGaugePa()));
  pf::FingerWorkspace ws(model);
  const double below = 0.9 * model.limitGaugePa();
  const pf::FingerState before = model.evaluate(below, ws);
  ASSERT_EQ(before.status, pf::EvaluationStatus::kOk);
  ASSERT_GT(before.tip_angle_rad, 0.0);
  for (double p : {model.limitGaugePa(), 1.5 * model.limitGaugePa()}) {
    const pf::FingerState& s = model.evaluate(p, ws);
    EXPECT_EQ(s.status, pf::EvaluationStatus::kBeyondLimitPoint);
    EXPECT_EQ(s.gauge_pa, below);
    EXPECT_EQ(s.tip_angle_rad, before.tip_angle_rad);
    EXPECT_TRUE(s.backbone_m.isApprox(before.backbone_m, 0.0));
  }
  EXPECT_STREQ(pf::evaluationStatusName(pf::EvaluationStatus::kBeyondLimitPoint), "beyond limit point");
  // Back below the limit: a shape again.
  EXPECT_EQ(model.evaluate(0.5 * model.limitGaugePa(), ws).status, pf::EvaluationStatus::kOk);
  EXPECT_TRUE(std::isnan(model.tipAngleAt(model.limitGaugePa())));
  std::vector<double> q(7);
  EXPECT_FALSE(model.jointAnglesAt(model.limitGaugePa(), q.data()));
  EXPECT_TRUE(model.jointAnglesAt(below, q.data()));
}

TEST(MembraneModel, BatchMatchesEvaluateBitForBitAndMarksTheLimit) {
  for (pf::SolverKind solver : {pf::SolverKind::kRobust, pf::SolverKind::kTable}) {
    pf::ModelOptions options;
    options.solver = solver;
    const pf::FingerModel model(membraneFinger(0), options);
    const double lim = model.limitGaugePa();
    const std::vector<double> p = {0.0, 1e-3, 0.1 * lim, 0.5 * lim, 0.999 * lim, lim, 2 * lim, -5.0, NAN};
    pf::BatchBuffers out(p.size(), model.chamberCount());
    pf::FingerWorkspace ws(model);
    model.evaluateMany(p.data(), p.size(), out.outputs(), ws);
    for (std::size_t i = 0; i < p.size(); ++i) {
      SCOPED_TRACE(p[i]);
      pf::FingerWorkspace one(model);
      const pf::FingerState& s = model.evaluate(p[i], one);
      ASSERT_EQ(out.status[i], static_cast<std::uint8_t>(s.status));
      if (s.status == pf::EvaluationStatus::kBeyondLimitPoint) {
        EXPECT_TRUE(std::isnan(out.tip_angle_rad[i]));
      } else if (s.status != pf::EvaluationStatus::kNotFinite) {
        EXPECT_EQ(out.tip_angle_rad[i], s.tip_angle_rad);
        for (int k = 0; k < 7; ++k) EXPECT_EQ(out.half_angle_rad[i * 7 + k], s.half_angle_rad[k]);
        for (int k = 0; k < 18; ++k) EXPECT_EQ(out.backbone_m[i * 18 + k], s.backbone_m.data()[k]);
      }
    }
    EXPECT_EQ(out.status[5], static_cast<std::uint8_t>(pf::EvaluationStatus::kBeyondLimitPoint));
    EXPECT_EQ(model.tableSegmentCount(), 0) << "the table holds the paper law only";
  }
}

TEST(MembraneModel, TheWholeFingerMatchesTheReferenceChain) {
  // The model's state against the reference's stretch and Wang's half angle per chamber, with unequal chambers too.
  for (const char* extra : {"", "chamber_height_m: [0.0115, 0.011, 0.0115, 0.012, 0.0115, 0.0115, 0.01]\n"}) {
    const pf::FingerParameters params = membraneFinger(50, extra);
    const pf::FingerModel model(params);
    pf::FingerWorkspace ws(model);
    for (double share : {0.01, 0.3, 0.9, 0.999999}) {
      const pf::FingerState& s = model.evaluate(share * model.limitGaugePa(), ws);
      ASSERT_EQ(s.status, pf::EvaluationStatus::kOk);
      for (int k = 0; k < params.chamber_count; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        const reference::Membrane rw{kMu, kThickness, params.chamber_height_m[kk], 50};
        const double d_ref = reference::membraneStretchExcess(rw, s.gauge_pa);
        const double theta_ref = reference::halfAngleForBulge(0.5 * params.chamber_height_m[kk] * d_ref,
                                                              params.chamber_gap_m[kk],
                                                              params.wall_critical_height_m[kk]);
        EXPECT_NEAR(s.half_angle_rad[k], theta_ref, 1e-12) << "chamber " << k + 1 << " at " << share;
        EXPECT_NEAR(s.stretch[k] - 1.0, d_ref, 1e-12 * d_ref);
      }
    }
  }
}

TEST(MembraneModel, ContactRuleReportsTheLimitPoint) {
  const pf::FingerModel model(membraneFinger(0));
  const pf::Obstacle disk = pf::Obstacle::disk(0.06, 0.03, 0.005);
  pf::ContactTracker tracker(model, disk);
  EXPECT_NE(tracker.solve(0.5 * model.limitGaugePa()).status, pf::ContactState::Status::kBeyondLimitPoint);
  EXPECT_EQ(tracker.solve(model.limitGaugePa()).status, pf::ContactState::Status::kBeyondLimitPoint);
}

TEST(MembraneModel, TheInverseRefusesTargetsBeyondTheLimit) {
  const pf::FingerModel model(membraneFinger(0));
  double p = 0;
  std::string why;
  const double reachable = model.tipAngleAt(0.7 * model.limitGaugePa());
  ASSERT_TRUE(model.gaugeForTipAngle(reachable, 1e6, p, why)) << why;
  EXPECT_NEAR(p, 0.7 * model.limitGaugePa(), 1e-12 * p);
  const double most = model.tipAngleBelowLimit();
  EXPECT_GT(most, reachable);
  EXPECT_FALSE(model.gaugeForTipAngle(most * 1.01, 1e6, p, why));
  EXPECT_NE(why.find("limit point"), std::string::npos) << why;
}

TEST(MembraneParameters, TheLawIsANamedChoiceAndTheDefaultStaysThePapers) {
  const pf::FingerParameters defaults = pf::FingerParameters::defaults();
  EXPECT_EQ(defaults.wall_law, pf::WallLaw::kPaper);
  EXPECT_TRUE(std::isinf(pf::FingerModel(defaults).limitGaugePa()));
  EXPECT_EQ(membraneFinger(0).wall_law, pf::WallLaw::kMembrane);
  pf::RawParameterMap raw;
  pf::parseParameterAssignment("wall_law=membrane", raw);
  EXPECT_EQ(pf::FingerParameters::fromRaw(raw).wall_law, pf::WallLaw::kMembrane);
  try {
    pf::parseParameterAssignment("wall_law=balloon", raw);
    FAIL() << "an unknown law was accepted";
  } catch (const pf::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("one of paper, membrane"), std::string::npos) << e.what();
  }
  try {
    pf::RawParameterMap yaml;
    pf::loadRawParametersFromYamlText("wall_law: 3\n", "f.yaml", yaml);
    FAIL() << "a number for a law was accepted";
  } catch (const pf::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("f.yaml: parameter 'wall_law' = '3'"), std::string::npos) << e.what();
  }
  // Written back by name.
  EXPECT_NE(pf::parametersToYaml(membraneFinger(0)).find("\nwall_law: membrane\n"), std::string::npos);
}

TEST(MembraneParameters, TheLeverMayExceedTheChamberOnlyUnderTheMembraneLaw) {
  EXPECT_NO_THROW(membraneFinger(0, "wall_critical_height_m: 0.02\n"));
  pf::RawParameterMap raw;
  raw["wall_critical_height_m"] = {{0.02}, false};
  EXPECT_THROW(pf::FingerParameters::fromRaw(raw), pf::ParameterError);
  pf::ModelOptions paper;
  paper.solver = pf::SolverKind::kPaper;
  try {
    pf::FingerModel model(membraneFinger(0), paper);
    FAIL() << "the paper solver took the membrane law";
  } catch (const pf::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("membrane"), std::string::npos) << e.what();
  }
}
