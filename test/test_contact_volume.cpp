// The supplied volume of a finger closing on an object, and the volume as the input there (contact.hpp:
// suppliedVolumeInContact, gaugeForVolumeInContact). The reference sums each wall's share of its chamber's growth by
// the paper law's ellipse, (pi/4) L e h per wall, from the bulges FingerModel::evaluate gives at the pressure and at
// each held joint's touch pressure.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "test_support.hpp"

namespace pf = pneumatic_finger;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTop = 294199.5;  // the paper finger's range (Pa gauge)

// The reference: every wall's bulge, free or held since its joint's touch, by the rule's own words.
double referenceVolume(const pf::FingerModel& model, const pf::ContactState& c, double gauge_pa) {
  const pf::FingerParameters& p = model.parameters();
  pf::FingerWorkspace ws(model);
  const pf::FingerState free_state = model.evaluate(gauge_pa, ws);
  double sum = 0.0;
  for (int k = 0; k < p.chamber_count; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    for (int joint = k; joint <= k + 1; ++joint) {  // 0-based joints k and k + 1: chamber k's two walls
      double h = free_state.bulge_m[k];
      if (joint < p.chamber_count && c.held[static_cast<std::size_t>(joint)]) {
        pf::FingerWorkspace at_touch(model);
        h = model.evaluate(c.held_since_gauge_pa[joint], at_touch).bulge_m[k];
      }
      sum += kPi / 4.0 * p.chamber_height_m[kk] * p.chamber_width_m[kk] * h;
    }
  }
  return sum + p.dead_volume_m3 * gauge_pa / (p.atmospheric_pressure_pa + gauge_pa);
}

pf::FingerParameters paperFingerWithGas() {
  pf::FingerParameters p = pf::FingerParameters::defaults();
  p.dead_volume_m3 = 2e-5;
  return p;
}

}  // namespace

// On a disk the held walls keep the bulge they touched with: the volume is the reference's, and less than the free
// finger's at the same pressure. Out of reach it is the free finger's.
TEST(ContactVolume, HeldWallsKeepTheBulgeTheyTouchedWith) {
  const pf::FingerModel model(paperFingerWithGas());
  pf::ContactTracker tracker(model, pf::Obstacle::disk(0.075, 0.035, 0.01));
  for (double gauge_pa : {1.0e5, 1.6e5, 2.0e5, 2.4e5}) {
    const pf::ContactState c = tracker.solve(gauge_pa);
    const double v = pf::suppliedVolumeInContact(model, c, gauge_pa), ref = referenceVolume(model, c, gauge_pa);
    EXPECT_NEAR(v, ref, 1e-12 * ref) << gauge_pa;
    if (c.status == pf::ContactState::Status::kInContact) {
      EXPECT_LT(v, model.suppliedVolumeAt(gauge_pa)) << gauge_pa;
    }
  }
  EXPECT_EQ(tracker.solve(2.4e5).status, pf::ContactState::Status::kInContact);
  pf::ContactTracker far(model, pf::Obstacle::disk(0.5, 0.5, 0.01));
  const double free_v = model.suppliedVolumeAt(2e5);
  EXPECT_NEAR(pf::suppliedVolumeInContact(model, far.solve(2e5), 2e5), free_v, 1e-14 * free_v);
}

// A touch holds each wall where it was, so the volume does not jump there: across the first touch it moves by what
// the free finger's moves.
TEST(ContactVolume, TheVolumeDoesNotJumpAtATouch) {
  const pf::FingerModel model(paperFingerWithGas());
  pf::ContactTracker tracker(model, pf::Obstacle::disk(0.075, 0.035, 0.01));
  const double touch = tracker.solve(kTop).first_touch_gauge_pa;
  ASSERT_TRUE(std::isfinite(touch));
  const double below = touch * (1 - 1e-9), above = touch * (1 + 1e-9);
  const double jump = pf::suppliedVolumeInContact(model, tracker.solve(above), above) -
                      pf::suppliedVolumeInContact(model, tracker.solve(below), below);
  const double free_step = model.suppliedVolumeAt(above) - model.suppliedVolumeAt(below);
  EXPECT_GE(jump, 0.0);
  EXPECT_LE(jump, 1.01 * free_step);
}

// Driven by volume: the pressure found gives the volume back, paper and membrane law; what cannot be taken is
// refused with the reason.
TEST(ContactVolume, TheVolumeAsTheInputGivesThePressureBack) {
  for (const pf::FingerParameters& p : {paperFingerWithGas(), pf_test::membraneFinger(50.0, "dead_volume_m3: 2e-5\n")}) {
    const pf::FingerModel model(p);
    pf::ContactTracker tracker(model, pf::Obstacle::disk(0.075, 0.035, 0.01));
    auto contact_at = [&](double gauge) { return tracker.solve(gauge); };
    const double top = std::fmin(kTop, model.belowLimitGaugePa());
    ASSERT_EQ(tracker.solve(top).status, pf::ContactState::Status::kInContact) << pf::wallLawName(p.wall_law);
    const double most = pf::suppliedVolumeInContact(model, tracker.solve(top), top);
    double gauge = 0.0;
    std::string why;
    for (double share : {0.0, 0.2, 0.6, 0.95, 1.0}) {
      ASSERT_TRUE(pf::gaugeForVolumeInContact(model, contact_at, share * most, kTop, gauge, why)) << why;
      EXPECT_NEAR(pf::suppliedVolumeInContact(model, tracker.solve(gauge), gauge), share * most, 1e-12 * most)
          << share;
    }
    EXPECT_FALSE(pf::gaugeForVolumeInContact(model, contact_at, 1.01 * most, kTop, gauge, why));
    EXPECT_NE(why.find("is more than the finger takes on the object up to"), std::string::npos) << why;
    for (double bad : {-1e-6, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
      EXPECT_FALSE(pf::gaugeForVolumeInContact(model, contact_at, bad, kTop, gauge, why)) << bad;
      EXPECT_NE(why.find("is not a finite volume >= 0"), std::string::npos) << why;
    }
  }
}

// Hard cases: an obstacle the straight finger already overlaps (reported, not solved: the free finger's volume), the
// volume at the first touch itself (the pressure of the touch comes back), and no volume at all (rest).
TEST(ContactVolume, HardCasesTheOverlapTheTouchItselfAndRest) {
  const pf::FingerModel model(paperFingerWithGas());
  pf::ContactTracker overlapping(model, pf::Obstacle::disk(0.03, 0.0, 0.01));  // across the straight finger
  const pf::ContactState c = overlapping.solve(1e5);
  ASSERT_EQ(c.status, pf::ContactState::Status::kOverlapsAtRest);
  const double free_v = model.suppliedVolumeAt(1e5);
  EXPECT_NEAR(pf::suppliedVolumeInContact(model, c, 1e5), free_v, 1e-14 * free_v);
  pf::ContactTracker tracker(model, pf::Obstacle::disk(0.075, 0.035, 0.01));
  auto contact_at = [&](double p) { return tracker.solve(p); };
  const double touch = tracker.solve(kTop).first_touch_gauge_pa;
  const double at_touch = pf::suppliedVolumeInContact(model, tracker.solve(touch), touch);
  double gauge = -1.0;
  std::string why;
  ASSERT_TRUE(pf::gaugeForVolumeInContact(model, contact_at, at_touch, kTop, gauge, why)) << why;
  EXPECT_NEAR(gauge, touch, 1e-9 * touch);
  ASSERT_TRUE(pf::gaugeForVolumeInContact(model, contact_at, 0.0, kTop, gauge, why)) << why;
  EXPECT_EQ(gauge, 0.0);
}
