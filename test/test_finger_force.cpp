// The force model (docs/MODEL.md, "Force"): the straight finger's joint moments and the blocked tip force, against
// the quad-precision reference's free bulge (test/reference_quad.cpp) and the page's formulas written out here, and
// the static balance checked by explicit forward kinematics of the chain the force holds.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/obstacle.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "reference_quad.hpp"

namespace pf = pneumatic_finger;

namespace {

pf::FingerParameters parametersFrom(const std::string& yaml) {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlText(yaml, "test", raw);
  return pf::FingerParameters::fromRaw(raw);
}

// The strip of the free wall beyond the contact plane (2a, m), from the reference's bulge h: the paper law's half
// ellipse of semi-axes R, R + h cut R + c from its centre, or the membrane's sphere of radius R + h (at most R).
double referenceStrip(double h, double r, double c, bool membrane) {
  if (h <= c) return 0.0;
  const long double R = r, H = h, C = c;
  const long double chord = std::sqrt((R + H) * (R + H) - (R + C) * (R + C));
  return static_cast<double>(2 * (membrane ? std::min(chord, R) : R / (R + H) * chord));
}

// F = sum_j M_j l_j w_j / sum_j l_j^2 w_j for the joints' moments M (joint 1 first), the segments Z, share s0.
double referenceTipForce(const std::vector<double>& moment, const std::vector<double>& z, double s0) {
  long double num = 0, den = 0, l = 0;
  for (int j = static_cast<int>(z.size()) - 1; j >= 0; --j) {
    l += z[static_cast<std::size_t>(j)];
    const long double w = j == 0 ? 1 + s0 : 2;
    num += moment[static_cast<std::size_t>(j)] * l * w;
    den += l * l * w;
  }
  return static_cast<double>(num / den);
}

}  // namespace

// The package's finger (paper law): the blocked force at pressures well past contact, where the strip is well
// conditioned, against the reference's bulge and the formula.
TEST(FingerForce, PaperFingerBlockedForceMatchesTheReference) {
  const pf::FingerParameters p = pf::FingerParameters::defaults();
  const pf::FingerModel model(p);
  const reference::ChamberGeometry chamber{p.chamber_height_m[0], p.wall_critical_height_m[0], p.chamber_gap_m[0],
                                           p.shear_modulus_pa[0]};
  for (double gauge_pa = 2 * model.contactGaugePa(); gauge_pa <= 3e5; gauge_pa *= 1.07) {
    const double h = reference::chamberChain(gauge_pa, p.atmospheric_pressure_pa, chamber).bulge_m;
    const double strip = referenceStrip(h, 0.5 * p.chamber_height_m[0], p.chamber_gap_m[0], false);
    const double m = gauge_pa * strip * p.chamber_width_m[0] * p.wall_critical_height_m[0];
    const double expected = referenceTipForce(std::vector<double>(7, m), p.segment_length_m, p.base_wall_share);
    EXPECT_NEAR(model.blockedTipForceN(gauge_pa), expected, 1e-12 * expected) << gauge_pa;
    std::vector<double> moments(7);
    model.straightJointMomentsNm(gauge_pa, moments.data());
    for (double mj : moments) EXPECT_NEAR(mj, m, 1e-12 * m) << gauge_pa;
  }
}

// A membrane wall (Gent, no limit point within the sweep) likewise, with the strip capped at the wall's height.
TEST(FingerForce, MembraneFingerBlockedForceMatchesTheReference) {
  const pf::FingerParameters p =
      parametersFrom("wall_law: membrane\nshear_modulus_pa: 2e4\nwall_thickness_m: 0.002\nwall_locking_jm: 6\n"
                     "chamber_gap_m: 0.0003\n");
  const pf::FingerModel model(p);
  const reference::Membrane wall{2e4, 0.002, p.chamber_height_m[0], 6};
  const double r = 0.5 * p.chamber_height_m[0];
  bool capped = false;
  for (double gauge_pa = 2 * model.contactGaugePa(); gauge_pa <= 4e4; gauge_pa *= 1.05) {
    const double h = r * reference::membraneStretchExcess(wall, gauge_pa);
    const double strip = referenceStrip(h, r, p.chamber_gap_m[0], true);
    capped = capped || strip == 2 * r;
    const double m = gauge_pa * strip * p.chamber_width_m[0] * p.wall_critical_height_m[0];
    const double expected = referenceTipForce(std::vector<double>(7, m), p.segment_length_m, p.base_wall_share);
    EXPECT_NEAR(model.blockedTipForceN(gauge_pa), expected, 1e-12 * expected) << gauge_pa;
  }
  EXPECT_TRUE(capped) << "the sweep never reached the strip's cap (the wall's height)";
}

// Unequal chambers: the weaker of two facing walls bounds a joint's moment, and the force is the planar balance of the
// chain. Checked by forward kinematics: joints turned by (M_j - F l_j) w_j (times a small scale) leave the tip where
// the plate holds it, to first order.
TEST(FingerForce, UnequalChambersBalanceTheChainWithTheTipHeld) {
  const pf::FingerParameters p = parametersFrom(
      "chamber_width_m: [0.007, 0.007, 0.006, 0.007, 0.008, 0.007, 0.007]\n"
      "chamber_gap_m: [0.00005, 0.00005, 0.00005, 0.00004, 0.00005, 0.00005, 0.00005]\n"
      "segment_length_m: [0.010, 0.010, 0.012, 0.010, 0.010, 0.009, 0.010]\n"
      "base_wall_share: 0.3\nshear_modulus_pa: 2.2e8\n");
  const pf::FingerModel model(p);
  const double gauge_pa = 2e5;
  std::vector<double> moments(7);
  model.straightJointMomentsNm(gauge_pa, moments.data());
  for (double m : moments) ASSERT_GT(m, 0.0) << "every wall pair must touch for this test";
  for (int j = 0; j < 7; ++j) {
    auto wall_moment = [&](int k) {
      const auto uk = static_cast<std::size_t>(k);
      const reference::ChamberGeometry c{p.chamber_height_m[uk], p.wall_critical_height_m[uk], p.chamber_gap_m[uk],
                                         p.shear_modulus_pa[uk]};
      const double h = reference::chamberChain(gauge_pa, p.atmospheric_pressure_pa, c).bulge_m;
      return gauge_pa * referenceStrip(h, 0.5 * p.chamber_height_m[uk], p.chamber_gap_m[uk], false) *
             p.chamber_width_m[uk] * p.wall_critical_height_m[uk];
    };
    const double expected = std::min(wall_moment(std::max(j - 1, 0)), wall_moment(j));
    EXPECT_NEAR(moments[static_cast<std::size_t>(j)], expected, 1e-12 * expected) << "joint " << j + 1;
  }
  const double force = model.blockedTipForceN(gauge_pa);
  EXPECT_NEAR(force, referenceTipForce(moments, p.segment_length_m, p.base_wall_share), 1e-12 * force);
  // The balance itself: the joints' turns under moment less tip force, through sin, move the tip only to second
  // order in the scale eps (y ~ eps^2 l); the force 1 % off moves it by eps * (1 % of the load's lever).
  auto tip_y = [&](double f, double eps) {
    long double angle = 0, y = 0, l = 0;
    std::vector<long double> lever(7);
    for (int j = 6; j >= 0; --j) lever[static_cast<std::size_t>(j)] = (l += p.segment_length_m[static_cast<std::size_t>(j)]);
    for (std::size_t j = 0; j < 7; ++j) {
      angle += eps * (moments[j] - f * lever[j]) * (j == 0 ? 1 + p.base_wall_share : 2.0);
      y += p.segment_length_m[j] * std::sin(angle);
    }
    return static_cast<double>(y);
  };
  const double eps = 1e-3 / moments[3];  // joint turns of about a milliradian
  EXPECT_LT(std::fabs(tip_y(force, eps)), 1e-3 * std::fabs(tip_y(1.01 * force, eps)));
}

// Below contact the walls do not touch: no force, exactly. A vacuum likewise (+0, not -0). NaN in, NaN out.
TEST(FingerForce, NoContactVacuumAndNaN) {
  const pf::FingerModel model(pf::FingerParameters::defaults());
  EXPECT_EQ(model.blockedTipForceN(0.0), 0.0);
  EXPECT_EQ(model.blockedTipForceN(0.999 * model.contactGaugePa()), 0.0);
  EXPECT_EQ(model.blockedTipForceN(model.contactGaugePa()), 0.0);
  EXPECT_GT(model.blockedTipForceN(1.001 * model.contactGaugePa()), 0.0);
  EXPECT_FALSE(std::signbit(model.blockedTipForceN(-5000.0)));
  EXPECT_EQ(model.blockedTipForceN(-5000.0), 0.0);
  EXPECT_TRUE(std::isnan(model.blockedTipForceN(std::numeric_limits<double>::quiet_NaN())));
}

// At a wall's limit point the free wall snaps; a held one cannot, and the part of its balloon beyond the contact plane
// is flattened: the whole wall, 2R tall, presses with P at the lever b. So the blocked force jumps at the limit point
// to F = P (2R e b) sum(l w)/sum(l^2 w), by hand from the geometry, for a Neo-Hookean wall (which balloons without
// bound) and for a Gent wall on its far branch (whose sphere's chord at the plane is past R as well).
TEST(FingerForce, TheBlockedForceJumpsAtTheLimitPointToTheWholeWall) {
  for (const char* lock : {"wall_locking_jm: 0\n", "wall_locking_jm: 50\n"}) {
    const pf::FingerParameters p =
        parametersFrom(std::string("wall_law: membrane\nshear_modulus_pa: 2e4\nwall_thickness_m: 0.002\n") + lock);
    const pf::FingerModel balloon(p);
    const double limit = balloon.limitGaugePa();
    ASSERT_TRUE(std::isfinite(limit)) << lock;
    std::vector<double> moments(7);
    for (const double gauge_pa : {limit, 1.01 * limit, 2.0 * limit}) {
      balloon.straightJointMomentsNm(gauge_pa, moments.data());
      double lw = 0, l2w = 0, l = 0;
      for (int j = 6; j >= 0; --j) {
        const auto uj = static_cast<std::size_t>(j);
        l += p.segment_length_m[uj];
        const double w = j == 0 ? 1.0 + p.base_wall_share : 2.0;
        lw += l * w;
        l2w += l * l * w;
        const double whole_wall = gauge_pa * p.chamber_height_m[uj] * p.chamber_width_m[uj] * p.wall_critical_height_m[uj];
        EXPECT_NEAR(moments[uj], whole_wall, 1e-14 * whole_wall) << lock << gauge_pa;
      }
      const double expected = gauge_pa * p.chamber_height_m[0] * p.chamber_width_m[0] * p.wall_critical_height_m[0] * lw / l2w;
      EXPECT_NEAR(balloon.blockedTipForceN(gauge_pa), expected, 1e-13 * expected) << lock << gauge_pa;
    }
    const double below = balloon.blockedTipForceN(0.999 * limit), at = balloon.blockedTipForceN(limit);
    EXPECT_GT(below, 0.0) << lock;
    EXPECT_GT(at, below) << lock << ": the strip, 2 min(a, R) just below the limit, is the whole wall at it";
  }
}

namespace {

// The contact rule's state for an obstacle at a pressure (from scratch).
pf::ContactState contactAt(const pf::FingerModel& model, double gauge_pa, const pf::Obstacle& obstacle) {
  return pf::ContactSolver(model).solve(gauge_pa, obstacle);
}

// How far each contact point moves into the object (along its segment's flexion-side normal) when the joints turn by
// dq: the backbone rebuilt by forward kinematics with q + dq, each contact point carried rigidly by its segment.
std::vector<double> contactMotion(const pf::FingerParameters& p, const pf::ContactState& c, const std::vector<double>& dq) {
  const int n = p.chamber_count;
  auto backbone = [&](const std::vector<double>& q, std::vector<Eigen::Vector2d>& o, std::vector<double>& theta) {
    o.assign(static_cast<std::size_t>(n + 2), Eigen::Vector2d::Zero());
    theta.assign(static_cast<std::size_t>(n + 1), 0.0);
    o[1] = Eigen::Vector2d(p.base_segment_length_m, 0.0);
    for (int i = 1; i <= n; ++i) {
      theta[static_cast<std::size_t>(i)] = theta[static_cast<std::size_t>(i - 1)] + q[static_cast<std::size_t>(i - 1)];
      const double t = theta[static_cast<std::size_t>(i)], z = p.segment_length_m[static_cast<std::size_t>(i - 1)];
      o[static_cast<std::size_t>(i + 1)] = o[static_cast<std::size_t>(i)] + z * Eigen::Vector2d(std::cos(t), std::sin(t));
    }
  };
  std::vector<double> q(static_cast<std::size_t>(n)), q2(q);
  for (int j = 0; j < n; ++j) q[static_cast<std::size_t>(j)] = c.joint_angle_rad[j];
  for (int j = 0; j < n; ++j) q2[static_cast<std::size_t>(j)] = q[static_cast<std::size_t>(j)] + dq[static_cast<std::size_t>(j)];
  std::vector<Eigen::Vector2d> o, o2;
  std::vector<double> th, th2;
  backbone(q, o, th);
  backbone(q2, o2, th2);
  std::vector<double> into;
  for (std::size_t k = 0; k < c.contact_points_m.size(); ++k) {
    const auto m = static_cast<std::size_t>(c.contact_segments[k]);
    const double turn = th2[m] - th[m];
    const Eigen::Vector2d arm = c.contact_points_m[k] - o[m];
    const Eigen::Vector2d moved = o2[m] + Eigen::Rotation2Dd(turn) * arm;
    const Eigen::Vector2d d = (o[m + 1] - o[m]).normalized();
    into.push_back((moved - c.contact_points_m[k]).dot(Eigen::Vector2d(-d.y(), d.x())));
  }
  return into;
}

}  // namespace

// A plate just above the straight finger's tip, across it (the published blocked-force test): the contact rule holds
// every joint at the first flexion, and the contact force at the tip is then the blocked tip force.
TEST(FingerForce, APlateAtTheTipPressesWithTheBlockedTipForce) {
  const pf::FingerParameters p = pf::FingerParameters::defaults();
  const pf::FingerModel model(p);
  const double tip_x = 0.085;
  const pf::Obstacle plate = pf::Obstacle::polygon(
      {{tip_x - 0.005, 1e-6}, {tip_x + 0.005, 1e-6}, {tip_x + 0.005, 0.01}, {tip_x - 0.005, 0.01}});
  for (double gauge_pa : {5e4, 1e5, 1.96133e5}) {
    const pf::ContactState c = contactAt(model, gauge_pa, plate);
    ASSERT_EQ(c.status, pf::ContactState::Status::kInContact) << gauge_pa;
    ASSERT_EQ(c.contact_points_m.size(), 1u);
    EXPECT_EQ(c.contact_segments[0], p.chamber_count) << "the tip segment touches";
    std::vector<double> f;
    pf::contactNormalForcesN(model, gauge_pa, c, f);
    ASSERT_EQ(f.size(), 1u);
    const double blocked = model.blockedTipForceN(gauge_pa);
    EXPECT_NEAR(f[0], blocked, 1e-3 * blocked) << gauge_pa;
  }
}

// A disk the finger closes on: the forces hold the chain so that no contact point moves along its normal (to first
// order, by forward kinematics), which a force 1 % off does not; they are positive and rise with the pressure.
TEST(FingerForce, ContactForcesBalanceTheHeldChain) {
  const pf::FingerParameters p = pf::FingerParameters::defaults();
  const pf::FingerModel model(p);
  const pf::Obstacle disk = pf::Obstacle::disk(0.075, 0.035, 0.01);
  double previous = 0.0;
  for (double gauge_pa : {1.6e5, 2.0e5, 2.4e5}) {
    const pf::ContactState c = contactAt(model, gauge_pa, disk);
    ASSERT_EQ(c.status, pf::ContactState::Status::kInContact);
    std::vector<double> f;
    pf::contactNormalForcesN(model, gauge_pa, c, f);
    ASSERT_EQ(f.size(), c.contact_points_m.size());
    EXPECT_GT(f.back(), previous) << gauge_pa;
    previous = f.back();
    std::vector<double> moment(7);
    model.heldJointMomentsNm(gauge_pa, c.held_since_gauge_pa.data(), moment.data());
    // Each joint turns by its moment less the contact forces' torques (the force on the finger points out of the
    // object, against the segment's flexion-side normal), times its compliance; eps keeps the turns near 1e-4 rad.
    auto turns = [&](double scale) {
      std::vector<double> dq(7);
      for (int j = 0; j < 7; ++j) {
        double torque = 0.0;
        for (std::size_t k = 0; k < f.size(); ++k) {
          const auto m = static_cast<std::size_t>(c.contact_segments[k]);
          if (static_cast<std::size_t>(j) >= m) continue;
          const Eigen::Vector2d d = (c.backbone_m.col(m + 1) - c.backbone_m.col(m)).normalized();
          const Eigen::Vector2d force = -scale * f[k] * Eigen::Vector2d(-d.y(), d.x());
          const Eigen::Vector2d arm = c.contact_points_m[k] - Eigen::Vector2d(c.backbone_m.col(j + 1));
          torque += arm.x() * force.y() - arm.y() * force.x();
        }
        dq[static_cast<std::size_t>(j)] = 1e-4 / moment[3] * (moment[static_cast<std::size_t>(j)] + torque) *
                                          model.jointComplianceWeight(j);
      }
      return dq;
    };
    const std::vector<double> held = contactMotion(p, c, turns(1.0)), off = contactMotion(p, c, turns(1.01));
    for (std::size_t k = 0; k < f.size(); ++k) {
      if (f[k] == 0.0) continue;  // a contact let go may move away
      EXPECT_LT(std::fabs(held[k]), 1e-3 * std::fabs(off[k])) << gauge_pa << " contact " << k;
    }
  }
}

// No contact, no force; a NaN pressure gives NaN forces, not made-up ones.
TEST(FingerForce, ContactForcesOnlyInContact) {
  const pf::FingerModel model(pf::FingerParameters::defaults());
  std::vector<double> f{1.0};
  pf::contactNormalForcesN(model, 1e5, contactAt(model, 1e5, pf::Obstacle::disk(0.5, 0.5, 0.01)), f);
  EXPECT_TRUE(f.empty());
  const pf::ContactState c = contactAt(model, 2e5, pf::Obstacle::disk(0.075, 0.035, 0.01));
  pf::contactNormalForcesN(model, std::numeric_limits<double>::quiet_NaN(), c, f);
  ASSERT_FALSE(f.empty());
  for (double v : f) EXPECT_TRUE(std::isnan(v));
}

// The pressure for a grip force: the force there is the one asked for, and just below it less; a force beyond the range
// is refused with the most the finger gives, and a force that is not > 0 by name.
TEST(FingerForce, ThePressureForAContactForce) {
  const pf::FingerModel model(pf::FingerParameters::defaults());
  pf::ContactTracker tracker(model, pf::Obstacle::disk(0.075, 0.035, 0.01));
  auto contact_at = [&](double p) { return tracker.solve(p); };
  const double most = pf::totalContactForceN(model, 294199.5, tracker.solve(294199.5));
  ASSERT_GT(most, 0.0);
  double gauge = 0;
  std::string why;
  for (double share : {0.1, 0.5, 0.9}) {
    ASSERT_TRUE(pf::gaugeForContactForce(model, contact_at, share * most, 294199.5, gauge, why)) << why;
    EXPECT_NEAR(pf::totalContactForceN(model, gauge, tracker.solve(gauge)), share * most, 1e-6 * most) << share;
    EXPECT_LT(pf::totalContactForceN(model, gauge - 100.0, tracker.solve(gauge - 100.0)), share * most) << share;
  }
  EXPECT_FALSE(pf::gaugeForContactForce(model, contact_at, 2 * most, 294199.5, gauge, why));
  EXPECT_NE(why.find("presses with at most"), std::string::npos) << why;
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    EXPECT_FALSE(pf::gaugeForContactForce(model, contact_at, bad, 294199.5, gauge, why)) << bad;
    EXPECT_NE(why.find("is not a finite force > 0"), std::string::npos) << why;
  }
}
