// The contact rule (core/contact.hpp) against an independent reference written here: a fine pressure scan with its
// own geometry and its own bisection. Then the rule's properties and its special cases.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/finger_model.hpp"

namespace pf = pneumatic_finger;

namespace {

struct Disk {
  double x, y, r;
};

// The reference: its own backbone and distance, a scan of 4000 pressures, and 200 bisection steps per touch.
struct Reference {
  std::vector<double> q;
  std::vector<bool> held;
  double first_touch = NAN;
};

std::vector<std::pair<double, double>> chain(const pf::FingerParameters& p, const std::vector<double>& q) {
  std::vector<std::pair<double, double>> o = {{0.0, 0.0}, {p.base_segment_length_m, 0.0}};
  double angle = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    angle += q[i];
    o.push_back({o.back().first + p.segment_length_m[i] * std::cos(angle),
                 o.back().second + p.segment_length_m[i] * std::sin(angle)});
  }
  return o;
}

double distanceToSegment(const Disk& d, std::pair<double, double> a, std::pair<double, double> b) {
  const double ux = b.first - a.first, uy = b.second - a.second;
  double t = ((d.x - a.first) * ux + (d.y - a.second) * uy) / (ux * ux + uy * uy);
  t = std::fmax(0.0, std::fmin(1.0, t));
  return std::hypot(a.first + t * ux - d.x, a.second + t * uy - d.y);
}

Reference reference(const pf::FingerParameters& params, double pressure, const Disk& disk) {
  const int n = params.chamber_count;
  pf::FingerModel model(params);
  pf::FingerWorkspace ws(model);
  auto free = [&](double p) {
    const pf::FingerState& s = model.evaluate(p, ws);
    return std::vector<double>(s.joint_angle_rad.data(), s.joint_angle_rad.data() + n);
  };
  Reference r;
  r.held.assign(static_cast<std::size_t>(n), false);
  std::vector<double> frozen_q(static_cast<std::size_t>(n), 0.0);
  int frozen = 0;
  auto config = [&](double p) {
    std::vector<double> q = free(p);
    for (int i = 0; i < frozen; ++i) q[static_cast<std::size_t>(i)] = frozen_q[static_cast<std::size_t>(i)];
    return q;
  };
  auto penetrates = [&](double p) {
    const auto o = chain(params, config(p));
    for (int k = frozen + 1; k <= n; ++k) {
      if (distanceToSegment(disk, o[static_cast<std::size_t>(k)], o[static_cast<std::size_t>(k + 1)]) <= disk.r) return true;
    }
    return false;
  };
  const int steps = 4000;
  double previous = 0.0;
  for (int i = 1; i <= steps && frozen < n; ++i) {
    const double p = pressure * i / steps;
    if (!penetrates(p)) {
      previous = p;
      continue;
    }
    double lo = previous, hi = p;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      (penetrates(mid) ? hi : lo) = mid;
    }
    if (std::isnan(r.first_touch)) r.first_touch = lo;
    const std::vector<double> q = config(lo);
    const auto o = chain(params, q);
    int m = 0;
    for (int k = frozen + 1; k <= n; ++k) {
      if (distanceToSegment(disk, o[static_cast<std::size_t>(k)], o[static_cast<std::size_t>(k + 1)]) - disk.r <= 1e-12) m = k;
    }
    for (int k = 0; k < m; ++k) frozen_q[static_cast<std::size_t>(k)] = q[static_cast<std::size_t>(k)];
    frozen = std::max(frozen, m);
    previous = lo;
    i = static_cast<int>(std::floor(lo / pressure * steps));  // scan on from the touch
  }
  r.q = config(pressure);
  for (int k = 0; k < frozen; ++k) r.held[static_cast<std::size_t>(k)] = true;
  return r;
}

const pf::FingerParameters kFinger = pf::FingerParameters::defaults();

// The solver at 2 kg/cm^2 on disk @p d against the reference: every joint to 1e-12 rad, the held joints, and the first
// touch (its pressure to 1e-9 relative, or none for both). Returns the solver's state.
pf::ContactState expectMatchesReference(const pf::FingerParameters& params, const pf::ContactSolver& solver,
                                        const Disk& d) {
  const pf::ContactState got = solver.solve(196133.0, pf::Obstacle::disk(d.x, d.y, d.r));
  const Reference want = reference(params, 196133.0, d);
  for (int i = 0; i < params.chamber_count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    EXPECT_NEAR(got.joint_angle_rad[i], want.q[k], 1e-12) << "disk " << d.x << "," << d.y << ", joint " << i + 1;
    EXPECT_EQ(got.held[k], want.held[k]) << "disk " << d.x << "," << d.y << ", joint " << i + 1;
  }
  EXPECT_EQ(std::isnan(got.first_touch_gauge_pa), std::isnan(want.first_touch)) << "disk " << d.x << "," << d.y;
  if (!std::isnan(want.first_touch)) {
    EXPECT_NEAR(got.first_touch_gauge_pa, want.first_touch, 1e-9 * want.first_touch);
  }
  return got;
}

}  // namespace

// Joint 1 with a turning base face (theta_0 = s0 theta_1): the half-angle search turns segment 1 by (1 + s0) theta,
// and a touch on segment 1 holds q_1 at the model's own value. Disks touched first by segments 1, 3 and 6 and the tip.
TEST(Contact, TurningBaseFaceMatchesTheReference) {
  pf::RawParameterMap raw;
  raw["base_wall_share"] = {{0.3}, false};
  const pf::FingerParameters finger = pf::FingerParameters::fromRaw(raw);
  pf::FingerModel model(finger);
  const pf::ContactSolver solver(model);
  const std::vector<Disk> disks = {{0.02, 0.0035, 0.003}, {0.0388324, 0.00650505, 0.003},
                                   {0.0632674, 0.0211602, 0.006}, {0.075, 0.035, 0.01}};
  int held_first = 0;
  for (const Disk& d : disks) {
    const pf::ContactState got = expectMatchesReference(finger, solver, d);
    EXPECT_FALSE(std::isnan(got.first_touch_gauge_pa)) << "every disk here is reached";
    held_first += got.held[0];
  }
  EXPECT_EQ(held_first, 4) << "every disk holds joint 1";
}

TEST(Contact, MatchesTheIndependentReferenceForDisksAcrossTheFinger) {
  pf::FingerModel model(kFinger);
  const pf::ContactSolver solver(model);
  // Disks on the strain-limited side that the curling finger reaches first with segment 3, 5, 6 and 7 (found by
  // placing them 0.1 mm from a segment's middle at 1.2e5 Pa), one it never reaches, and one wide one.
  const std::vector<Disk> disks = {{0.0388324, 0.00650505, 0.003}, {0.0567121, 0.0136807, 0.003},
                                   {0.0632674, 0.0211602, 0.006}, {0.075, 0.035, 0.01},
                                   {0.05, 0.02, 0.004},           {0.02, 0.03, 0.015}};
  int walls_in_contact = 0;
  for (const Disk& d : disks) {
    walls_in_contact += expectMatchesReference(kFinger, solver, d).status == pf::ContactState::Status::kInContact;
  }
  EXPECT_GE(walls_in_contact, 4) << "the cases must exercise the rule";
}

// The general path (unequal chambers: no single half angle; a grid in sqrt(P) and bisection) against the same
// reference: the last chamber's wall gap 20 % wider.
TEST(Contact, UnequalChambersTakeTheGeneralPathAndMatchTheReference) {
  pf::FingerParameters params = kFinger;
  params.chamber_gap_m.back() *= 1.2;
  pf::FingerModel model(params);
  ASSERT_EQ(model.distinctChamberCount(), 2);
  const pf::ContactSolver solver(model);
  int touched = 0;
  for (const Disk& d : {Disk{0.0567121, 0.0136807, 0.003}, Disk{0.0632674, 0.0211602, 0.006}, Disk{0.075, 0.035, 0.01}}) {
    touched += expectMatchesReference(params, solver, d).status == pf::ContactState::Status::kInContact;
  }
  EXPECT_GE(touched, 2) << "the cases must exercise the rule";
}

TEST(Contact, NoJointPassesItsFreeAngleNothingPenetratesAndNoJointGoesBack) {
  pf::FingerModel model(kFinger);
  const pf::ContactSolver solver(model);
  for (const pf::Obstacle& obstacle :
       {pf::Obstacle::disk(0.07, 0.03, 0.004), pf::Obstacle::ellipse(0.07, 0.035, 0.008, 0.004, 0.3),
        pf::Obstacle::polygon({{0.06, 0.03}, {0.08, 0.03}, {0.08, 0.05}, {0.06, 0.05}})}) {
    ASSERT_EQ(obstacle.problem(), "");
    Eigen::VectorXd previous = Eigen::VectorXd::Zero(7);
    for (double p = 0; p <= 294199.5; p += 4903.325) {
      const pf::ContactState s = solver.solve(p, obstacle);
      Eigen::VectorXd free(7);
      ASSERT_TRUE(model.jointAnglesAt(p, free.data()));
      for (int i = 0; i < 7; ++i) {
        EXPECT_LE(s.joint_angle_rad[i], free[i]) << "P = " << p;
        EXPECT_GE(s.joint_angle_rad[i], previous[i]) << "P = " << p << " joint " << i + 1;
      }
      for (int k = 0; k <= 7; ++k) {
        EXPECT_GT(obstacle.clearance(s.backbone_m.col(k), s.backbone_m.col(k + 1)), -1e-12) << "P = " << p;
      }
      previous = s.joint_angle_rad;
    }
  }
}

TEST(Contact, ARoundEllipseIsTheDisk) {
  pf::FingerModel model(kFinger);
  const pf::ContactSolver solver(model);
  const pf::ContactState disk = solver.solve(2e5, pf::Obstacle::disk(0.07, 0.03, 0.004));
  const pf::ContactState ellipse = solver.solve(2e5, pf::Obstacle::ellipse(0.07, 0.03, 0.004, 0.004, 1.0));
  ASSERT_EQ(disk.status, pf::ContactState::Status::kInContact);
  for (int i = 0; i < 7; ++i) EXPECT_NEAR(ellipse.joint_angle_rad[i], disk.joint_angle_rad[i], 1e-12);
}

TEST(Contact, AnObstacleOutOfReachLeavesTheFreeFinger) {
  pf::FingerModel model(kFinger);
  pf::FingerWorkspace ws(model);
  const pf::ContactSolver solver(model);
  // 85 mm of finger; a disk whose nearest point is 85.001 mm from the mount.
  const pf::ContactState s = solver.solve(196133.0, pf::Obstacle::disk(0.0, 0.090001, 0.005));
  EXPECT_EQ(s.status, pf::ContactState::Status::kFree);
  EXPECT_TRUE(std::isnan(s.first_touch_gauge_pa));
  EXPECT_EQ(s.touches, 0);
  const pf::FingerState& free = model.evaluate(196133.0, ws);
  for (int i = 0; i < 7; ++i) EXPECT_EQ(s.joint_angle_rad[i], free.joint_angle_rad[i]);
  EXPECT_NEAR((s.backbone_m - free.backbone_m).cwiseAbs().maxCoeff(), 0.0, 1e-15);
}

TEST(Contact, JustOutOfReachOfTheCurlingFingerIsNoTouch) {
  // A disk that the free finger at 2 kg/cm^2 misses by 1 um: no contact, the free finger.
  pf::FingerModel model(kFinger);
  pf::FingerWorkspace ws(model);
  const pf::ContactSolver solver(model);
  const pf::FingerState& s = model.evaluate(196133.0, ws);
  const Eigen::Vector2d tip = s.tip();
  const Eigen::Vector2d ahead(std::cos(s.tip_angle_rad), std::sin(s.tip_angle_rad));
  const double r = 0.003;
  const Eigen::Vector2d c = tip + (r + 1e-6) * ahead;
  EXPECT_EQ(solver.solve(196133.0, pf::Obstacle::disk(c.x(), c.y(), r)).status, pf::ContactState::Status::kFree);
  // And 1 um closer it is touched, by the tip's segment: every joint is held.
  const Eigen::Vector2d closer = tip + (r - 1e-6) * ahead;
  const pf::ContactState t = solver.solve(196133.0, pf::Obstacle::disk(closer.x(), closer.y(), r));
  EXPECT_EQ(t.status, pf::ContactState::Status::kInContact);
  for (bool h : t.held) EXPECT_TRUE(h);
  ASSERT_EQ(t.contact_points_m.size(), 1u);
  EXPECT_NEAR((t.contact_points_m[0] - t.backbone_m.col(8)).norm(), 0.0, 1e-4) << "the tip touches";
}

TEST(Contact, AnObstacleOverlappingTheStraightFingerIsReportedNotSolved) {
  pf::FingerModel model(kFinger);
  const pf::ContactSolver solver(model);
  const pf::ContactState s = solver.solve(1e5, pf::Obstacle::disk(0.04, 0.001, 0.002));
  EXPECT_EQ(s.status, pf::ContactState::Status::kOverlapsAtRest);
}

TEST(Contact, BadObstaclesAreNamed) {
  EXPECT_NE(pf::Obstacle::disk(0, 0, -1).problem().find("radius"), std::string::npos);
  EXPECT_NE(pf::Obstacle::disk(NAN, 0, 1).problem().find("finite"), std::string::npos);
  EXPECT_NE(pf::Obstacle::polygon({{0, 0}, {1, 0}}).problem().find("3 vertices"), std::string::npos);
  EXPECT_NE(pf::Obstacle::polygon({{0, 0}, {2, 0}, {1, 0.1}, {2, 2}, {0, 2}}).problem().find("convex"), std::string::npos);
  EXPECT_NE(pf::Obstacle::ellipse(0, 0, 1, 0, 0).problem().find("semi-axes"), std::string::npos);
  EXPECT_EQ(pf::Obstacle::polygon({{0, 2}, {2, 2}, {2, 0}, {0, 0}}).problem(), "");  // clockwise is fine
}

// Hard case: a touch exactly at a joint. A narrow wedge whose point sits on joint 4's path at 1.2e5 Pa, opening
// along that path: joint 4 is the first point of the backbone to reach it, where segments 3 and 4 meet, so both
// touch at once and joints 1..4 freeze; joints 5..7 go on.
TEST(Contact, ATouchExactlyAtAJointFreezesTheJointsUpToIt) {
  pf::FingerModel model(kFinger);
  pf::FingerWorkspace ws(model);
  const pf::ContactSolver solver(model);
  const double pj = 1.2e5;
  auto joint4 = [&](double p) { return Eigen::Vector2d(model.evaluate(p, ws).backbone_m.col(4)); };
  const Eigen::Vector2d apex = joint4(pj);
  const Eigen::Vector2d v = (joint4(pj * (1 + 1e-6)) - joint4(pj * (1 - 1e-6))).normalized();
  const Eigen::Vector2d w(-v.y(), v.x());
  const pf::Obstacle wedge = pf::Obstacle::polygon({apex, apex + 0.005 * v + 0.0002 * w, apex + 0.005 * v - 0.0002 * w});
  ASSERT_EQ(wedge.problem(), "");
  const pf::ContactState s = solver.solve(196133.0, wedge);
  ASSERT_EQ(s.status, pf::ContactState::Status::kInContact);
  EXPECT_NEAR(s.first_touch_gauge_pa, pj, 1e-6 * pj);
  ASSERT_GE(s.contact_points_m.size(), 1u);
  EXPECT_NEAR((s.contact_points_m[0] - apex).norm(), 0.0, 1e-9);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(s.held[static_cast<std::size_t>(i)]) << "joint " << i + 1;
  // Held at their angles at the touch; the joints after 4 kept following the pressure until they touched or not.
  Eigen::VectorXd at_touch(7);
  ASSERT_TRUE(model.jointAnglesAt(s.first_touch_gauge_pa, at_touch.data()));
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(s.joint_angle_rad[i], at_touch[i], 1e-12);
  EXPECT_GT(s.joint_angle_rad[4], at_touch[4]) << "joint 5 went on";
}

// Hard case: a grazing touch. A disk ahead of the tip, tangent to the tip's path at 1.2e5 Pa on the side the path
// bends away from: the clearance comes down to 0 at that pressure and rises again, never negative. It counts as the
// touch (the finger reached the object), and every joint freezes there.
TEST(Contact, AGrazingTouchCounts) {
  pf::FingerModel model(kFinger);
  pf::FingerWorkspace ws(model);
  const pf::ContactSolver solver(model);
  const double pg = 1.2e5;
  auto tip = [&](double p) { return Eigen::Vector2d(model.evaluate(p, ws).tip()); };
  const Eigen::Vector2d t0 = tip(pg);
  const Eigen::Vector2d tangent = (tip(pg * (1 + 1e-6)) - tip(pg * (1 - 1e-6))).normalized();
  Eigen::Vector2d normal(-tangent.y(), tangent.x());
  // The side the path bends away from: the second difference points the other way.
  const Eigen::Vector2d bend = tip(pg * 1.05) + tip(pg * 0.95) - 2 * t0;
  if (normal.dot(bend) > 0) normal = -normal;
  const double r = 0.002;
  const Eigen::Vector2d c = t0 + r * normal;
  const pf::ContactState s = solver.solve(196133.0, pf::Obstacle::disk(c.x(), c.y(), r));
  ASSERT_EQ(s.status, pf::ContactState::Status::kInContact);
  EXPECT_NEAR(s.first_touch_gauge_pa, pg, 1e-4 * pg);
  for (bool h : s.held) EXPECT_TRUE(h);
  // Below the grazing pressure the finger is free.
  EXPECT_EQ(solver.solve(0.99 * pg, pf::Obstacle::disk(c.x(), c.y(), r)).status, pf::ContactState::Status::kFree);
}

// The tracker keeps the touch events it has found; in any order of pressures it answers what the from-scratch
// solver answers, bit for bit.
TEST(Contact, TheTrackerAnswersTheSolverBitForBitInAnyOrder) {
  pf::FingerModel model(kFinger);
  const pf::ContactSolver solver(model);
  for (const pf::Obstacle& obstacle : {pf::Obstacle::disk(0.0388324, 0.00650505, 0.003),
                                       pf::Obstacle::disk(0.075, 0.035, 0.01), pf::Obstacle::disk(0.0, 0.2, 0.01),
                                       pf::Obstacle::ellipse(0.07, 0.035, 0.008, 0.004, 0.3)}) {
    pf::ContactTracker tracker(model, obstacle);
    for (double p : {196133.0, 50000.0, 150000.0, 120000.0, 294199.5, 0.0, 130000.0, 196133.0, 98066.5}) {
      const pf::ContactState want = solver.solve(p, obstacle);
      const pf::ContactState got = tracker.solve(p);
      EXPECT_EQ(got.status, want.status) << p;
      EXPECT_EQ(got.held, want.held) << p;
      EXPECT_EQ(got.touches, want.touches) << p;
      for (int i = 0; i < 7; ++i) EXPECT_EQ(got.joint_angle_rad[i], want.joint_angle_rad[i]) << p << " joint " << i + 1;
      if (want.touches > 0) {
        EXPECT_EQ(got.first_touch_gauge_pa, want.first_touch_gauge_pa) << p;
      }
    }
  }
}
