// FingerModel::evaluateMany (finger_batch.cpp): every batch path (scalar, generic packs, AVX2, AVX-512) answers,
// pressure by pressure, the bits FingerModel::evaluate answers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/stages.hpp"
#include "test_support.hpp"

namespace pf = pneumatic_finger;

namespace {

// Pressures a batch meets: the validated range, docs/MODEL.md's hard cases (near rest, around contact, the
// resolvent band, theta -> pi/2 up to the rare branches), vacuum and refused values, in an order that puts every kind
// in every lane of a pack, and a count that leaves the last pack partly filled.
std::vector<double> batchPressures(const pf::FingerModel& model) {
  std::vector<double> p;
  for (int i = 0; i <= 400; ++i) p.push_back(196133.0 * i / 400);
  for (double x = 1e-12; x < 10; x *= 7) p.push_back(x);
  const double pc = model.contactGaugePa();
  for (int k = 1; k <= 16; ++k) {
    p.push_back(pc * (1 - std::pow(10.0, -k)));
    p.push_back(pc * (1 + std::pow(10.0, -k)));
  }
  p.push_back(pc);
  p.push_back(std::nextafter(pc, 0.0));
  p.push_back(std::nextafter(pc, INFINITY));
  for (double e = 5.0; e <= 300.0; e += 0.37) p.push_back(std::pow(10.0, e));  // through g > 1e30 and the big bulge
  for (double x : {-1.0, -1e5, -0.0, 0.0, std::numeric_limits<double>::quiet_NaN(), double(INFINITY),
                   -double(INFINITY), std::numeric_limits<double>::max(), std::numeric_limits<double>::denorm_min()}) {
    p.push_back(x);
  }
  // Packs whose lanes straddle a limit where the shared arithmetic switches form (simd_math.hpp): the arctangent's and
  // joint 1's direction's (both at tan(theta) = 1/8) and joint 1's base-face sine and cosine (s0 theta = 1/8, above
  // it), alternately just below and just above it.
  const pf::FingerParameters& params = model.parameters();
  const double turns = 2 * params.chamber_count - 1 + params.base_wall_share;
  std::vector<double> limits = {std::atan(0.125)};
  if (params.base_wall_share > 0.0 && 0.125 / params.base_wall_share < 1.5) limits.push_back(0.125 / params.base_wall_share);
  for (double theta : limits) {
    for (int k = 1; k <= 12; ++k) {
      for (double side : {-1.0, 1.0}) {
        double gauge = 0.0;
        std::string why;
        if (model.gaugeForTipAngle(turns * theta * (1.0 + side * k * 1e-9), 1e300, gauge, why)) p.push_back(gauge);
      }
    }
  }
  // ... and the series of stages 2-3 (s = sqrt(g/3) = 1/20, at P (2 P_o + P) = 3 P_o mu / 400).
  const double po = params.atmospheric_pressure_pa, mu = params.shear_modulus_pa[0];
  const double at_series_limit = std::sqrt(po * po + 3.0 * po * mu * 0.05 * 0.05) - po;
  for (int k = 1; k <= 12; ++k) {
    for (double side : {-1.0, 1.0}) p.push_back(at_series_limit * (1.0 + side * std::pow(10.0, -k - 3)));
  }
  p.push_back(std::nextafter(at_series_limit, 0.0));
  p.push_back(std::nextafter(at_series_limit, INFINITY));
  if (p.size() % 8 == 0) p.push_back(12345.0);
  return p;
}

using Rows = pf::BatchBuffers;

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Compares row i of a batch with evaluate() on a fresh model (no cache in play); returns how many values differ.
int compareRow(const pf::FingerModel& single, pf::FingerWorkspace& single_ws, const Rows& rows, std::size_t i,
               double gauge_pa, const std::string& what) {
  const int n = single.chamberCount();
  const auto un = static_cast<std::size_t>(n);
  const pf::FingerState& s = single.evaluate(gauge_pa, single_ws);
  int differ = 0;
  auto check = [&](double got, double want, const char* field, std::size_t k) {
    if (!sameBits(got, want)) {
      if (++differ <= 3) {
        ADD_FAILURE() << what << ": P = " << gauge_pa << " Pa, " << field << "[" << k << "] = " << got
                      << ", evaluate() gives " << want;
      }
    }
  };
  const pf::EvaluationStatus want = !std::isfinite(gauge_pa) ? pf::EvaluationStatus::kNotFinite : s.status;
  if (want == pf::EvaluationStatus::kNotFinite || want == pf::EvaluationStatus::kSolverFailure ||
      want == pf::EvaluationStatus::kBeyondLimitPoint) {
    // Refused, or no answer (the paper's solver at some pressures, a membrane past its limit point without a far
    // branch): NaN throughout, where evaluate() keeps its previous state.
    EXPECT_EQ(rows.status[i], static_cast<int>(want)) << what;
    for (std::size_t k = 0; k < un; ++k) EXPECT_TRUE(std::isnan(rows.half_angle_rad[i * un + k])) << what;
    for (std::size_t k = 0; k < 2 * (un + 2); ++k) EXPECT_TRUE(std::isnan(rows.backbone_m[i * 2 * (un + 2) + k]));
    EXPECT_TRUE(std::isnan(rows.tip_angle_rad[i]));
    return 0;
  }
  EXPECT_EQ(rows.status[i], static_cast<int>(s.status)) << what << " at P = " << gauge_pa;
  for (std::size_t k = 0; k < un; ++k) {
    const auto e = static_cast<Eigen::Index>(k);
    check(rows.stretch[i * un + k], s.stretch[e], "stretch", k);
    check(rows.bulge_m[i * un + k], s.bulge_m[e], "bulge_m", k);
    check(rows.half_angle_rad[i * un + k], s.half_angle_rad[e], "half_angle_rad", k);
    check(rows.joint_angle_rad[i * un + k], s.joint_angle_rad[e], "joint_angle_rad", k);
  }
  for (std::size_t k = 0; k < 2 * (un + 2); ++k) {
    check(rows.backbone_m[i * 2 * (un + 2) + k], s.backbone_m.data()[k], "backbone_m", k);
  }
  check(rows.tip_angle_rad[i], s.tip_angle_rad, "tip_angle_rad", 0);
  return differ;
}

void expectEveryPathMatchesEvaluate(const pf::FingerParameters& params, pf::SolverKind solver) {
  pf::ModelOptions options;
  options.solver = solver;
  pf::FingerModel batch(params, options);
  pf::FingerWorkspace batch_ws(batch);
  const std::vector<double> pressures = batchPressures(batch);
  int paths_run = 0;
  for (pf::BatchPath path : {pf::BatchPath::kBest, pf::BatchPath::kScalar, pf::BatchPath::kGeneric,
                             pf::BatchPath::kAvx2, pf::BatchPath::kAvx512}) {
    if (!pf::batchPathAvailable(path)) continue;  // this CPU lacks it; the generic pack runs the same code
    ++paths_run;
    Rows rows(pressures.size(), params.chamber_count);
    batch.evaluateMany(pressures.data(), pressures.size(), rows.outputs(), batch_ws, path);
    int differ = 0;
    for (std::size_t i = 0; i < pressures.size(); ++i) {
      pf::FingerModel single(params, options);
      pf::FingerWorkspace single_ws(single);
      differ += compareRow(single, single_ws, rows, i, pressures[i], std::string(pf::batchPathName(path)) + "/" +
                                                          pf::solverName(solver));
    }
    EXPECT_EQ(differ, 0) << pf::batchPathName(path) << ": values that differ from evaluate()";
  }
  EXPECT_GE(paths_run, 3);
  // The batch neither reads nor writes the workspace's cached state.
  EXPECT_EQ(batch_ws.computationCount(), 0);
}

}  // namespace

TEST(Batch, EveryPathAnswersTheBitsOfEvaluateForIdenticalChambers) {
  expectEveryPathMatchesEvaluate(pf::FingerParameters::defaults(), pf::SolverKind::kRobust);
}

TEST(Batch, OtherChamberCountsAndSegmentLengths) {
  // 1 chamber (no direction product at all), 3, 9 and 33 (powers r^2..r^32 of the direction tree), unequal lengths.
  for (int n : {1, 3, 9, 33}) {
    pf::RawParameterMap raw;
    pf::parseParameterAssignment("chamber_count=" + std::to_string(n), raw);
    std::string lengths = "segment_length_m=[";
    for (int i = 0; i < n; ++i) lengths += (i ? "," : "") + std::to_string(0.01 * (1.0 + 0.1 * i));
    pf::parseParameterAssignment(lengths + "]", raw);
    const pf::FingerParameters p = pf::FingerParameters::fromRaw(raw);
    SCOPED_TRACE("N = " + std::to_string(n));
    expectEveryPathMatchesEvaluate(p, pf::SolverKind::kRobust);
  }
}

TEST(Batch, TurningBaseFace) {
  pf::RawParameterMap raw;
  raw["base_wall_share"] = {{0.3}, false};
  expectEveryPathMatchesEvaluate(pf::FingerParameters::fromRaw(raw), pf::SolverKind::kRobust);
  raw["base_wall_share"] = {{1.0}, false};
  expectEveryPathMatchesEvaluate(pf::FingerParameters::fromRaw(raw), pf::SolverKind::kRobust);
}

TEST(Batch, UnequalChambersAndOtherSolversGoOneAtATime) {
  pf::FingerParameters unequal = pf::FingerParameters::defaults();
  unequal.chamber_gap_m[3] *= 1.5;
  expectEveryPathMatchesEvaluate(unequal, pf::SolverKind::kRobust);
  expectEveryPathMatchesEvaluate(pf::FingerParameters::defaults(), pf::SolverKind::kTable);
  expectEveryPathMatchesEvaluate(pf::FingerParameters::defaults(), pf::SolverKind::kPaper);
}

TEST(Batch, ZeroGapTakesTheSingleEvaluationsRareBranch) {
  pf::FingerParameters p = pf::FingerParameters::defaults();
  p.chamber_gap_m.assign(p.chamber_gap_m.size(), 0.0);
  expectEveryPathMatchesEvaluate(p, pf::SolverKind::kRobust);
}

namespace {

// Pressures a thin membrane's batch meets, in sequence: the near branch from rest to the limit point, its hard cases
// (near rest, the starting table's nodes and their neighbours, around the touch, just below the limit), then up
// through the snap and down the far branch past its turning point, vacuum and refused values, each kind in every
// lane of a pack; a count that leaves the last pack partly filled.
std::vector<double> membranePressures(const pf::FingerModel& model, const pf::FingerParameters& params) {
  const pf::MembraneWall wall =
      pf::membraneWall(params.shear_modulus_pa[0], params.wall_thickness_m[0], params.chamber_height_m[0],
                       params.wall_locking_jm, params.wall_law == pf::WallLaw::kThick);
  // Without a limit point, the top of the starting table (the lock's neighbourhood), or 100 kPa without a table.
  const double limit = std::isfinite(model.limitGaugePa()) ? model.limitGaugePa()
                       : wall.has_guess                    ? wall.guess_gauge_pa[31]
                                                           : 1e5;
  std::vector<double> p;
  for (int i = 0; i <= 300; ++i) p.push_back(0.999 * limit * i / 300);
  for (double x = 1e-12; x < 10; x *= 7) p.push_back(x);
  for (double g : wall.guess_gauge_pa) {
    if (!(g < model.limitGaugePa())) continue;
    for (double x : {g, std::nextafter(g, 0.0), std::nextafter(g, INFINITY)}) p.push_back(x);
  }
  const double pc = model.contactGaugePa();
  for (int k = 1; k <= 16; ++k) {
    p.push_back(pc * (1 - std::pow(10.0, -k)));
    p.push_back(pc * (1 + std::pow(10.0, -k)));
    p.push_back(limit * (1 - std::pow(10.0, -k)));
  }
  p.push_back(std::nextafter(limit, 0.0));
  for (double x : {-1.0, -1e5, -0.0, 0.0, std::numeric_limits<double>::quiet_NaN(), double(INFINITY),
                   -double(INFINITY), std::numeric_limits<double>::denorm_min()}) {
    p.push_back(x);
  }
  // Through the snap (or past the limit, where the law has no far branch) and down again, twice.
  for (int cycle = 0; cycle < 2; ++cycle) {
    for (int i = 0; i <= 60; ++i) p.push_back(1.5 * limit * i / 60);
    for (int i = 60; i >= 0; --i) p.push_back(1.5 * limit * i / 60);
  }
  if (std::isfinite(model.farTurningGaugePa())) {
    const double turning = model.farTurningGaugePa();
    for (double x : {limit, std::nextafter(turning, INFINITY), turning, 0.5 * turning, limit, 0.5 * turning}) {
      p.push_back(x);
    }
  }
  if (p.size() % 8 == 0) p.push_back(0.25 * limit);
  return p;
}

// Every batch path against evaluate() on one workspace, row by row in the same order (the branches are the path's).
void expectMembraneBatchMatchesEvaluate(const pf::FingerParameters& params) {
  pf::FingerModel batch(params);
  const std::vector<double> pressures = membranePressures(batch, params);
  int paths_run = 0;
  for (pf::BatchPath path : {pf::BatchPath::kBest, pf::BatchPath::kScalar, pf::BatchPath::kGeneric,
                             pf::BatchPath::kAvx2, pf::BatchPath::kAvx512}) {
    if (!pf::batchPathAvailable(path)) continue;
    ++paths_run;
    pf::FingerWorkspace batch_ws(batch);
    Rows rows(pressures.size(), params.chamber_count);
    batch.evaluateMany(pressures.data(), pressures.size(), rows.outputs(), batch_ws, path);
    pf::FingerModel single(params);
    pf::FingerWorkspace single_ws(single);
    int differ = 0;
    for (std::size_t i = 0; i < pressures.size(); ++i) {
      differ += compareRow(single, single_ws, rows, i, pressures[i], pf::batchPathName(path));
    }
    EXPECT_EQ(differ, 0) << pf::batchPathName(path) << ": values that differ from evaluate()";
    EXPECT_EQ(batch_ws.snappedThrough(), single_ws.snappedThrough()) << "the branch the sequence ends on";
  }
  EXPECT_GE(paths_run, 3);
}

}  // namespace

TEST(Batch, TheMembranesPacksAnswerTheBitsOfEvaluateAlongThePath) {
  // Gent with a far branch (J_m = 50), Neo-Hookean (no far branch: past the limit nothing), Gent without a limit
  // point (J_m = 6: P rises to the lock), a finger whose walls touch early (a narrow gap); the thick wall, Gent and
  // Neo-Hookean, and bent by its inner face (the packs' own bulge, not the outer face's lane by lane); a share of the
  // bulge below 1 (wall_bulge_share), on a thick wall near its fold and on a thin one.
  struct Finger {
    double jm;
    const char* extra;
    pf::WallLaw law;
  };
  for (const Finger& f : {Finger{50, "", pf::WallLaw::kMembrane}, Finger{0, "", pf::WallLaw::kMembrane},
                          Finger{6, "", pf::WallLaw::kMembrane},
                          Finger{50, "chamber_gap_m: 0.0002\n", pf::WallLaw::kMembrane},
                          Finger{50, "", pf::WallLaw::kThick}, Finger{0, "", pf::WallLaw::kThick},
                          Finger{50, "wall_flexion_face: inner\n", pf::WallLaw::kThick},
                          Finger{26, "wall_bulge_share: 0.2\n", pf::WallLaw::kThick},
                          Finger{6, "wall_bulge_share: 0.3\n", pf::WallLaw::kMembrane}}) {
    SCOPED_TRACE(std::string(pf::wallLawName(f.law)) + " J_m " + std::to_string(f.jm) + " " + f.extra);
    pf::FingerParameters params = pf_test::membraneFinger(f.jm, f.extra);
    params.wall_law = f.law;
    expectMembraneBatchMatchesEvaluate(params);
  }
}
