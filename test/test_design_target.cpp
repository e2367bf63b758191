// Design to spec (design_target.hpp): the search recovers a known design from its own quantity, its answer loads back
// to the same prediction, a target out of reach names the bound that stops it, and bad requests are refused.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <string>

#include "pneumatic_finger/calibration/design_target.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pf = pneumatic_finger;

namespace {

pf::FingerParameters epfl(const pf::RawParameterMap& extra = {}) {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/epfl_ecoflex30_c7.yaml", raw);
  for (const auto& [key, value] : extra) raw[key] = value;
  return pf::FingerParameters::fromRaw(raw);
}

pf::DesignRequest wallFor(const std::string& target, int count) {
  pf::DesignRequest r;
  r.targets = {pf::parseDesignTarget(target)};
  r.free = {{"drawing/wall_thickness_m", 0.0, 0.0}};
  r.chamber_counts = {count};
  return r;
}

}  // namespace

// A 5-chamber sibling with 5 mm walls snaps at S (its own model's snapGaugePa); asked for a snap at S from the 7-chamber
// file, the search returns 5 mm, and the written answer loads back to the same snap.
TEST(DesignTarget, FindsTheWallOfAKnownSiblingFromItsSnap) {
  const pf::FingerParameters sibling = epfl({{"drawing/chamber_count", {{5}, false}},
                                             {"drawing/wall_thickness_m", {{0.005}, false}}});
  const double snap_pa = pf::designQuantity(sibling, pf::parseDesignTarget("snap_gauge_pa=1"));
  const pf::DesignRequest request = wallFor("snap_gauge_pa=" + pf::formatExact(snap_pa), 5);
  const pf::DesignAnswer a = pf::designToTarget(epfl(), request);
  ASSERT_TRUE(a.met) << a.miss;
  EXPECT_EQ(a.chamber_count, 5);
  EXPECT_NEAR(a.values[0], 0.005, 0.005 * 1e-6);
  EXPECT_NEAR(a.reach, std::log(0.007 / 0.005), 1e-5);
  EXPECT_TRUE(a.at_bound.empty());
  // Written and read back: the design's own snap, to the bit of its written numbers.
  const pf::ParameterTree tree = pf::readParameterTree(YAML::Load(pf::designParameterYaml(a, request, 5e4)), "designed");
  const pf::FingerParameters loaded = pf::FingerParameters::fromRaw(tree.raw);
  EXPECT_EQ(pf::designQuantity(loaded, request.targets[0]), a.achieved[0]);
  EXPECT_EQ(tree.range.validated_max_gauge_pa, 0.0);  // no actuator's data validate a drawing not yet cast
  EXPECT_EQ(tree.range.max_gauge_pa, 5e4);
}

// Beyond the bounds: the nearest design, and the bound that stops it. The castable thickness bounds the wall below.
TEST(DesignTarget, ATargetOutOfReachGivesTheNearestAndItsBound) {
  pf::DesignRequest request = wallFor("snap_gauge_pa=90000", 5);
  request.free[0].hi = 0.012;
  request.validated_max_gauge_pa = 45000.0;  // the EPFL file's
  const pf::DesignAnswer a = pf::designToTarget(epfl(), request);
  EXPECT_FALSE(a.met);
  // Its snap lies beyond what the base actuator's data cover: said so.
  ASSERT_FALSE(a.notes.empty());
  EXPECT_NE(a.notes[0].find("above the base actuator's validated range (to 45000 Pa)"), std::string::npos) << a.notes[0];
  EXPECT_NEAR(a.values[0], 0.012, 1e-12);
  ASSERT_EQ(a.at_bound.size(), 1u);
  EXPECT_EQ(a.at_bound[0], "drawing/wall_thickness_m at its upper bound 0.012 m");
  EXPECT_NEAR(a.miss, 1.0 - a.achieved[0] / 90000.0, 1e-15);
  request = wallFor("snap_gauge_pa=1000", 5);  // a wall far thinner than can be cast
  request.castable_m = 0.002;
  const pf::DesignAnswer thin = pf::designToTarget(epfl(), request);
  EXPECT_FALSE(thin.met);
  EXPECT_NEAR(thin.values[0], 0.002, 1e-12);
  EXPECT_EQ(thin.at_bound[0], "drawing/wall_thickness_m at its lower bound 0.002 m");
}

// The bend at a pressure, a target of its own kind: the design's tip angle there is the target's.
TEST(DesignTarget, MeetsABendAtAPressure) {
  pf::DesignRequest request;
  request.targets = {pf::parseDesignTarget("tip_angle_rad@30000=0.5")};
  request.free = {{"drawing/cavity_height_m", 0.0, 0.0}};
  const pf::DesignAnswer a = pf::designToTarget(epfl(), request);
  ASSERT_TRUE(a.met) << a.miss;
  EXPECT_NEAR(a.achieved[0], 0.5, 0.5e-8);  // the search goes on to its numerical limit
  // The model every interface builds (with the wall's inverse, which the search skips: the same stretch within
  // 4e-15) gives the reported bend to 1e-12.
  pf::FingerModel model(a.parameters);
  pf::FingerWorkspace ws(model);
  EXPECT_NEAR(model.evaluate(30000.0, ws).tip_angle_rad, a.achieved[0], 1e-12);
}

TEST(DesignTarget, RefusesWhatItCannotSearch) {
  const auto refusal = [](auto&& call) {
    try {
      call();
    } catch (const pf::ParameterError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(refusal([] { pf::parseDesignTarget("snap_gauge_pa"); }).find("no '='"), std::string::npos);
  EXPECT_NE(refusal([] { pf::parseDesignTarget("tip_angle_rad=1"); }).find("tip_angle_rad needs '@'"),
            std::string::npos);
  EXPECT_NE(refusal([] { pf::parseDesignTarget("snap_gauge_pa@3=1"); }).find("takes no '@'"), std::string::npos);
  EXPECT_NE(refusal([] { pf::parseDesignTarget("snap_gauge_pa=nan"); }).find("'nan' is not a finite number"),
            std::string::npos);
  pf::DesignRequest request = wallFor("snap_gauge_pa=40000", 5);
  request.free = {{"chamber_gap_m", 0.0, 0.0}};
  EXPECT_NE(refusal([&] { pf::designToTarget(epfl(), request); }).find("--free chamber_gap_m: not a drawing size"),
            std::string::npos);
  request.free = {{"drawing/wall_thickness_m", 0.0, 0.0005}};
  EXPECT_NE(refusal([&] { pf::designToTarget(epfl(), request); }).find("hold no size"), std::string::npos);
  request.free = {{"drawing/wall_thickness_m", 0.012, 0.002}};
  EXPECT_NE(refusal([&] { pf::designToTarget(epfl(), request); }).find("=0.012:0.002: LO must be below HI"),
            std::string::npos);
  EXPECT_NE(refusal([&] { pf::designToTarget(pf::FingerParameters::defaults(), wallFor("snap_gauge_pa=1", 5)); })
                .find("no drawing"),
            std::string::npos);
}

// Two targets one free size cannot both meet: the front runs from the design that meets the first to the one that
// meets the second, no design on it beats another on both, and each design's reported quantities are its own.
TEST(DesignTarget, AParetoFrontOfTwoTargetsThatPullApart) {
  pf::DesignRequest request = wallFor("snap_gauge_pa=40000", 5);
  request.targets.push_back(pf::parseDesignTarget("tip_angle_rad@30000=0.6"));
  const std::vector<pf::DesignAnswer> front = pf::designParetoFront(epfl(), request, 8);
  ASSERT_GE(front.size(), 3u);
  EXPECT_LT(std::fabs(front.front().misses[0]), 1e-6);  // the snap met, the bend not
  EXPECT_GT(std::fabs(front.front().misses[1]), 0.1);
  EXPECT_LT(std::fabs(front.back().misses[1]), 1e-6);   // the bend met, the snap not
  for (std::size_t i = 0; i + 1 < front.size(); ++i) {
    // Along the front one miss falls as the other rises.
    EXPECT_LE(std::fabs(front[i].misses[0]), std::fabs(front[i + 1].misses[0]));
    EXPECT_GE(std::fabs(front[i].misses[1]), std::fabs(front[i + 1].misses[1]));
  }
  for (const pf::DesignAnswer& a : front) {
    for (std::size_t t = 0; t < 2; ++t) {
      EXPECT_EQ(pf::designQuantity(a.parameters, request.targets[t]), a.achieved[t]);
    }
  }
  request.targets.pop_back();
  EXPECT_THROW(pf::designParetoFront(epfl(), request, 8), pf::ParameterError);  // one target has no front
}

// A free size that moves no target would be set anywhere: refused, naming it. A designed finger that meets itself at
// a target's pressure is said so.
TEST(DesignTarget, SaysWhatADesignerMustKnow) {
  pf::DesignRequest request = wallFor("snap_gauge_pa=40000", 5);
  request.free = {{"drawing/roof_thickness_m", 0.0, 0.0}};  // this law's snap is the wall's, whatever the roof
  try {
    pf::designToTarget(epfl(), request);
    ADD_FAILURE() << "a roof that moves no snap was searched";
  } catch (const pf::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("--free drawing/roof_thickness_m: no target moves with it"), std::string::npos)
        << e.what();
  }
  request.targets = {pf::parseDesignTarget("tip_angle_rad@30000=10")};  // more than a finger can bend
  request.free = {{"drawing/wall_thickness_m", 0.0, 0.0}};
  const pf::DesignAnswer a = pf::designToTarget(epfl(), request);
  ASSERT_EQ(a.notes.size(), 1u);
  EXPECT_NE(a.notes[0].find("at 30000 Pa the designed finger meets itself"), std::string::npos) << a.notes[0];
  EXPECT_THROW(pf::parseDesignTarget("snap_gauge_pa=-5"), pf::ParameterError);
}

namespace {

// A grip target: a 20 g part of 30 mm lifted at 2 m/s^2 by the shipped gripper, held at most at the EPFL file's top.
pf::DesignRequest gripFor(const std::string& target) {
  pf::DesignRequest r = wallFor(target, 7);
  pf::attachGripPart(r.targets, "mass_kg=0.02,diameter_m=0.03,lift_mps2=2", 5e4);
  return r;
}

double gripOf(const pf::FingerParameters& p, const pf::DesignRequest& r) {
  return pf::holdingGaugePa(pf::FingerModel(p), r.targets[0].grip);
}

}  // namespace

// The lowest pressure that holds the part: lower than the base drawing's, the answer's own when its file is loaded
// back, and at an edge the search names (a thinner wall balloons before it holds) or at a bound.
TEST(DesignTarget, LowersThePressureThatHoldsAPart) {
  const pf::DesignRequest request = gripFor("grip_gauge_pa=min");
  const pf::DesignAnswer a = pf::designToTarget(epfl(), request);
  ASSERT_TRUE(a.met);
  const double base_pa = gripOf(epfl(), request);
  EXPECT_LT(a.achieved[0], 0.8 * base_pa) << "the 7 mm wall holds it at " << base_pa << " Pa";
  const pf::ParameterTree tree = pf::readParameterTree(YAML::Load(pf::designParameterYaml(a, request, 5e4)), "grip");
  EXPECT_NEAR(gripOf(pf::FingerParameters::fromRaw(tree.raw), request), a.achieved[0], 1e-12 * a.achieved[0]);
  // Each neighbour 1 % thinner or thicker (within the bounds) holds it higher, or not at all.
  for (const double step : {0.99, 1.01}) {
    const double wall = a.values[0] * step;
    if (wall < 0.007 / 4.0 || wall > 0.028) continue;
    const double p = gripOf(epfl({{"drawing/wall_thickness_m", {{wall}, false}}}), request);
    EXPECT_TRUE(std::isnan(p) || p > a.achieved[0]) << wall << " m holds at " << p << " Pa";
  }
  const bool edge = !a.notes.empty() && a.notes[0].find("1 % smaller gives no design") != std::string::npos;
  EXPECT_TRUE(edge || !a.at_bound.empty()) << "the answer says what stops it going lower";
}

// A grip pressure as a value is met like any other target, and joins a Pareto front; a lowest cannot.
TEST(DesignTarget, MeetsAGripPressureAndRefusesAGripWithoutItsPart) {
  const pf::DesignRequest request = gripFor("grip_gauge_pa=30000");
  const pf::DesignAnswer a = pf::designToTarget(epfl(), request);
  ASSERT_TRUE(a.met) << a.miss;
  EXPECT_NEAR(gripOf(a.parameters, request), 30000.0, 30000.0 * pf::kDesignTolerance);
  std::vector<pf::DesignTarget> targets = {pf::parseDesignTarget("grip_gauge_pa=min")};
  EXPECT_THROW(pf::attachGripPart(targets, "", 5e4), pf::ParameterError);  // no part
  targets = {pf::parseDesignTarget("snap_gauge_pa=40000")};
  EXPECT_THROW(pf::attachGripPart(targets, "mass_kg=0.02,diameter_m=0.03", 5e4), pf::ParameterError);  // no grip
  EXPECT_THROW(pf::parseDesignTarget("snap_gauge_pa=min"), pf::ParameterError);  // only a grip has a lowest
  pf::DesignRequest two = gripFor("grip_gauge_pa=min");
  two.targets.push_back(pf::parseDesignTarget("snap_gauge_pa=40000"));
  EXPECT_THROW(pf::designParetoFront(epfl(), two, 4), pf::ParameterError);
  pf::DesignRequest heavy = wallFor("grip_gauge_pa=min", 7);
  pf::attachGripPart(heavy.targets, "mass_kg=2,diameter_m=0.03", 5e4);
  try {
    pf::designToTarget(epfl(), heavy);
    ADD_FAILURE() << "a 2 kg part was held";
  } catch (const pf::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("the base drawing's grip: each finger must press with 9.80665 N"),
              std::string::npos) << e.what();
  }
}
