#include "pneumatic_finger/core/contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "pneumatic_finger/core/units.hpp"
#include "joint_chain.hpp"
#include "simd_math.hpp"
#include "touch_search.hpp"

namespace pneumatic_finger {

namespace {

// cos and sin of a joint or sample angle: the model's own series (simd_math.hpp, sinCosSmall; within 2 ulp of 1) on
// [0, pi/2], where a closing finger's angles lie (theta, q_1 = (1 + s0) theta, q_n = 2 theta); glibc's outside it. The
// series costs less than the two library calls, and the search runs it at every sample.
inline void cosSin(double x, double& cos_x, double& sin_x) {
  if (x >= 0.0 && x <= kHalfPi) {
    sinCosSmall(x, cos_x, sin_x);
  } else {
    cos_x = std::cos(x);
    sin_x = std::sin(x);
  }
}

using Vec = Eigen::Vector2d;

}  // namespace

ContactSolver::ContactSolver(const FingerModel& model) : model_(model) {
  const FingerParameters& p = model.parameters();
  length_m_ = p.lengthM();
  // The half-angle search needs one half angle for every free wall (identical chambers) and a forward model that
  // is the closed-form inverse's exact counterpart (the robust solver).
  uniform_ = model.distinctChamberCount() == 1 && model.options().solver == SolverKind::kRobust;
}

void ContactSolver::backbone(const JointAngles& q, BackbonePoints& points) const {
  const FingerParameters& p = model_.parameters();
  const int n = p.chamber_count;
  points.resize(2, n + 2);
  double x = p.base_segment_length_m, y = 0.0;
  points.col(0) = Vec::Zero();
  points.col(1) = Vec(x, y);
  // The direction turns by q_i at joint i (eq 38); a joint whose angle equals the previous one's (the free joints of
  // identical chambers, a frozen run) reuses its sine and cosine.
  double dir_c = 1.0, dir_s = 0.0, rot_c = 1.0, rot_s = 0.0;
  for (int i = 0; i < n; ++i) {
    if (i == 0 || q[i] != q[i - 1]) {
      cosSin(q[i], rot_c, rot_s);
    }
    advanceBackbone(rot_c, rot_s, p.segment_length_m[static_cast<std::size_t>(i)], dir_c, dir_s, x, y);
    points.col(i + 2) = Vec(x, y);
  }
}

namespace {

// The touch search's sampler for identical chambers with the robust solver: every free joint is a function of the one
// half angle theta (q_1 = (1 + s0) theta, q_n = 2 theta) and the pressure is theta's closed-form inverse, so the
// search runs in theta, where the backbone costs one sincos and no model solve. A point of the backbone moves at most
// speed = sum over free joints of (dq_i/dtheta) x (arc length from joint i to the tip) per radian: a clearance c rules
// out a touch for the next c / speed radians, so far obstacles are passed in a few long steps.
class HalfAngleSampler {
 public:
  HalfAngleSampler(const FingerParameters& par, double length_m, const Obstacle& obstacle, int frozen,
                   const JointAngles& frozen_q, BackbonePoints& points)
      : first(frozen + 1), n(par.chamber_count), par_(par), obstacle_(obstacle), points_(points) {
    placeFrozen(frozen_q);
    double rest = length_m - par.base_segment_length_m;  // arc length from joint i (at O_i) to the tip
    for (int i = 1; i <= n; ++i) {
      if (i >= first) speed += (i == 1 ? 1.0 + par.base_wall_share : 2.0) * rest;
      rest -= par.segment_length_m[static_cast<std::size_t>(i - 1)];
    }
    // A disk, the commonest section, is measured in squared distances (one square root per sample, no division:
    // the segments' lengths are fixed).
    disk_ = obstacle.asDisk(disk_center_, disk_radius_);
    for (int k = 1; k <= n; ++k) {
      const double z = par.segment_length_m[static_cast<std::size_t>(k - 1)];
      inv_length2_[static_cast<std::size_t>(k)] = 1.0 / (z * z);
    }
  }

  double clearance(double theta, int from, int to, int& segment, bool each) {
    double c1, s1;
    cosSin(theta, c1, s1);
    const double c2 = (c1 - s1) * (c1 + s1), s2 = 2.0 * s1 * c1;  // e^(2 i theta)
    // e^(i q_1), q_1 = theta_0 + theta; needed only while joint 1 is free.
    double q1_c = c1, q1_s = s1;
    if (par_.base_wall_share != 0.0 && first == 1) cosSin(par_.base_wall_share * theta + theta, q1_c, q1_s);
    double dc = dir0_c_, ds = dir0_s_;
    double c = INFINITY;
    for (int k = first; k <= to; ++k) {
      const double rc = k == 1 ? q1_c : c2, rs = k == 1 ? q1_s : s2;
      const double t = dc * rc - ds * rs;
      ds = ds * rc + dc * rs;
      dc = t;
      const double z = par_.segment_length_m[static_cast<std::size_t>(k - 1)];
      points_(0, k + 1) = points_(0, k) + z * dc;
      points_(1, k + 1) = points_(1, k) + z * ds;
      if (k < from) continue;
      const double ck = disk_ ? diskDistance2(k) : obstacle_.clearance(points_.col(k), points_.col(k + 1));
      if (ck < c) c = ck, segment = k;
      if (each) per_segment[static_cast<std::size_t>(k)] = disk_ ? std::sqrt(ck) - disk_radius_ : ck;
    }
    return disk_ ? std::sqrt(c) - disk_radius_ : c;
  }

  /// The held angles at the touch, as the model writes them: q_1 = theta_0 + theta (jointAnglesAt), q_n = 2 theta.
  void heldAngles(double theta, int frozen, int m, JointAngles& q) const {
    for (int i = frozen; i < m; ++i) q[i] = i == 0 ? par_.base_wall_share * theta + theta : 2.0 * theta;
  }

  const int first, n;
  const double step = 1e-3;  // rad of theta: the finest spacing of the samples
  const double x_cap = 1.5;  // rad: the model's range ends before pi/2, and the skips must not depend on the end
  double speed = 0.0;        // m/rad
  std::array<double, kMaxChamberCount + 1> per_segment{};

 private:
  // O_1..O_{first} and the direction after the held joints (no trigonometry for the first touch, where nothing is
  // held).
  void placeFrozen(const JointAngles& frozen_q) {
    points_.col(0) = Vec::Zero();
    points_.col(1) = Vec(par_.base_segment_length_m, 0.0);
    double dir0 = 0.0;
    for (int i = 0; i + 1 < first; ++i) {
      dir0 += frozen_q[i];
      double dir_c, dir_s;
      cosSin(dir0, dir_c, dir_s);
      points_.col(i + 2) = points_.col(i + 1) + par_.segment_length_m[static_cast<std::size_t>(i)] * Vec(dir_c, dir_s);
    }
    if (first > 1) cosSin(dir0, dir0_c_, dir0_s_);
  }

  // The squared distance from the disk's centre to segment k.
  double diskDistance2(int k) const {
    const Vec p = points_.col(k), d = points_.col(k + 1) - p, w = disk_center_ - p;
    const double t = std::clamp(w.dot(d) * inv_length2_[static_cast<std::size_t>(k)], 0.0, 1.0);
    return (w - t * d).squaredNorm();
  }

  const FingerParameters& par_;
  const Obstacle& obstacle_;
  BackbonePoints& points_;
  double dir0_c_ = 1.0, dir0_s_ = 0.0;
  bool disk_ = false;
  Vec disk_center_ = Vec::Zero();
  double disk_radius_ = 0.0;
  std::array<double, kMaxChamberCount + 1> inv_length2_{};  // 1..n
};

// The touch search's sampler for any other finger: the search runs in u = sqrt(P) (the angles grow like it), and
// every sample solves the model at P = u^2, holds joints 1..frozen, and places the backbone.
class PressureRootSampler {
 public:
  PressureRootSampler(const ContactSolver& solver, const FingerModel& model, const Obstacle& obstacle, int frozen,
                      const JointAngles& frozen_q, BackbonePoints& points)
      : first(frozen + 1), n(model.chamberCount()), solver_(solver), model_(model), obstacle_(obstacle),
        frozen_q_(frozen_q), q_(n), points_(points) {}

  double clearance(double u, int from, int to, int& segment, bool each) {
    if (!model_.jointAnglesAt(u * u, q_.data())) return -std::numeric_limits<double>::infinity();
    q_.head(first - 1) = frozen_q_.head(first - 1);
    solver_.backbone(q_, points_);
    double c = INFINITY;
    for (int k = from; k <= to; ++k) {
      const double ck = obstacle_.clearance(points_.col(k), points_.col(k + 1));
      if (ck < c) c = ck, segment = k;
      if (each) per_segment[static_cast<std::size_t>(k)] = ck;
    }
    return c;
  }

  /// The held angles at the touch: the free ones of the last sample (clearance() at the touch comes first).
  void heldAngles(double /*u*/, int frozen, int m, JointAngles& q) const {
    q.segment(frozen, m - frozen) = q_.segment(frozen, m - frozen);
  }

  const int first, n;
  const double step = 10.0;  // sqrt(Pa): 45 samples up to 2 kg/cm^2
  const double x_cap = INFINITY;
  const double speed = INFINITY;  // no bound: every step of the grid is sampled
  std::array<double, kMaxChamberCount + 1> per_segment{};

 private:
  const ContactSolver& solver_;
  const FingerModel& model_;
  const Obstacle& obstacle_;
  const JointAngles& frozen_q_;
  JointAngles q_;
  BackbonePoints& points_;
};

// The touch event the search finds: bracket, refine, then freeze at lo, the last shape clear of the obstacle, so that
// no joint passes its free angle and nothing penetrates. Segments as close as the touching one (to
// kTouchDistanceM) touch too: a touch at a joint holds both of its segments.
template <class Sampler>
TouchEvent searchTouch(Sampler& s, const Obstacle& obstacle, const BackbonePoints& points,
                       const JointAngles& frozen_q, double x0, double x_end, double& x_clear) {
  TouchEvent event;
  TouchBracket b = bracketTouch(s, x0, x_end);
  if (!b.found) {
    x_clear = b.clear;
    return event;
  }
  refineTouch(s, b);
  int seg = 0;
  const double touch_c = s.clearance(b.lo, s.first, s.n, seg, true);
  event.found = true;
  event.failed = !std::isfinite(touch_c);
  if (event.failed) return event;
  int m = seg;
  for (int k = seg + 1; k <= s.n; ++k) {
    if (s.per_segment[static_cast<std::size_t>(k)] <= touch_c + kTouchDistanceM) m = k;
  }
  event.search_x = b.lo;
  event.frozen = m;
  event.segment = seg;
  event.frozen_q = frozen_q;
  s.heldAngles(b.lo, s.first - 1, m, event.frozen_q);
  event.point_m = obstacle.nearestPoint(points.col(seg), points.col(seg + 1));
  return event;
}

}  // namespace

TouchEvent ContactSolver::findEvent(const Obstacle& obstacle, double from_x, int frozen, const JointAngles& frozen_q,
                                    double end_x, double& clear_x) const {
  BackbonePoints points(2, model_.chamberCount() + 2);
  TouchEvent event;
  if (uniform_) {
    HalfAngleSampler s(model_.parameters(), length_m_, obstacle, frozen, frozen_q, points);
    event = searchTouch(s, obstacle, points, frozen_q, from_x, end_x, clear_x);
  } else {
    PressureRootSampler s(*this, model_, obstacle, frozen, frozen_q, points);
    event = searchTouch(s, obstacle, points, frozen_q, from_x, end_x, clear_x);
  }
  if (event.found && !event.failed) event.failed = !gaugeAt(event.search_x, event.gauge_pa);
  return event;
}

double ContactSolver::searchVariable(double gauge_pa, double free_half_angle_rad) const {
  return uniform_ ? free_half_angle_rad : std::sqrt(gauge_pa);
}

bool ContactSolver::gaugeAt(double x, double& gauge_pa) const {
  if (!uniform_) {
    gauge_pa = x * x;
    return true;
  }
  return model_.gaugeForHalfAngle(x, gauge_pa);
}

ContactState ContactSolver::solve(double gauge_pa, const Obstacle& obstacle) const {
  ContactTracker tracker(model_, obstacle);
  return tracker.solve(gauge_pa);
}

ContactTracker::ContactTracker(const FingerModel& model, const Obstacle& obstacle)
    : solver_(model), obstacle_(obstacle) {
  const int n = model.chamberCount();
  frozen_q_ = JointAngles::Zero(n);
  // Model only what the scene needs: an obstacle beyond the finger's reach costs one comparison, once.
  out_of_reach_ = obstacle.distanceFromOrigin() > solver_.length_m_;
  if (out_of_reach_) return;
  // The straight finger's segments lie end to end along x: together, the one segment from the mount to the tip.
  overlaps_at_rest_ = obstacle.touches(Eigen::Vector2d::Zero(), Eigen::Vector2d(solver_.length_m_, 0.0));
}

ContactState ContactTracker::solve(double gauge_pa) {
  const FingerModel& model = solver_.model_;
  const int n = model.chamberCount();
  ContactState out;
  out.held.assign(static_cast<std::size_t>(n), false);
  out.held_since_gauge_pa.setConstant(n, std::numeric_limits<double>::quiet_NaN());
  const double pressure = std::max(gauge_pa, 0.0);
  out.joint_angle_rad.resize(n);  // the free angles first; the held ones are written over them below
  double free_half_angle_rad = 0.0;  // theta_1, the half angle of chamber 1's walls (all of them, identical chambers)
  std::array<double, kMaxChamberCount> half;
  const bool beyond_limit = pressure >= model.limitGaugePa();
  if (beyond_limit || !model.jointAnglesAt(pressure, out.joint_angle_rad.data(), half.data())) {
    out.status = beyond_limit ? ContactState::Status::kBeyondLimitPoint : ContactState::Status::kSolverFailure;
    out.joint_angle_rad.setZero();
    solver_.backbone(out.joint_angle_rad, out.backbone_m);
    return out;
  }
  free_half_angle_rad = half[0];
  if (!out_of_reach_ && overlaps_at_rest_) out.status = ContactState::Status::kOverlapsAtRest;
  if (out_of_reach_ || overlaps_at_rest_) {
    solver_.backbone(out.joint_angle_rad, out.backbone_m);
    return out;
  }
  findEventsUpTo(pressure, free_half_angle_rad);
  if (failed_) {
    out.status = ContactState::Status::kSolverFailure;
    solver_.backbone(out.joint_angle_rad, out.backbone_m);
    return out;
  }
  const int frozen = applyEventsUpTo(pressure, out);
  solver_.backbone(out.joint_angle_rad, out.backbone_m);
  out.status = frozen > 0 ? ContactState::Status::kInContact : ContactState::Status::kFree;
  return out;
}

// The touch events do not depend on the pressure asked for: they are found once, in order, and kept. A pressure
// within what is already known costs only the free model and the backbone.
void ContactTracker::findEventsUpTo(double pressure, double free_half_angle_rad) {
  const int n = solver_.model_.chamberCount();
  while (!failed_ && (events_.empty() || events_.back().gauge_pa <= pressure) && frozen_ < n &&
         pressure > clear_gauge_pa_) {
    const double from = events_.empty() ? 0.0 : events_.back().search_x;
    double clear = 0.0, gauge = 0.0;
    TouchEvent e = solver_.findEvent(obstacle_, from, frozen_, frozen_q_,
                                     solver_.searchVariable(pressure, free_half_angle_rad), clear);
    const double clear_gauge_pa = !e.found && solver_.gaugeAt(clear, gauge) ? std::max(gauge, pressure) : pressure;
    if (!e.found) {
      clear_gauge_pa_ = clear_gauge_pa;  // no touch after the last event up to here
      break;
    }
    if (e.failed) {
      failed_ = true;
      break;
    }
    frozen_ = e.frozen;
    frozen_q_ = e.frozen_q;  // same size: no allocation
    events_.push_back(std::move(e));
    clear_gauge_pa_ = 0.0;  // a new segment of the search starts at this event
  }
}

// The events up to @p pressure into @p out: the touches, and the held joints at the angles they froze at. Returns how
// many joints, from the mount, are held.
int ContactTracker::applyEventsUpTo(double pressure, ContactState& out) const {
  int frozen = 0;
  for (const TouchEvent& e : events_) {
    if (e.gauge_pa > pressure) break;
    if (out.touches == 0) out.first_touch_gauge_pa = e.gauge_pa;
    ++out.touches;
    out.contact_points_m.push_back(e.point_m);
    out.contact_segments.push_back(e.segment);
    out.held_since_gauge_pa.segment(frozen, e.frozen - frozen).setConstant(e.gauge_pa);
    frozen = e.frozen;
    out.joint_angle_rad.head(frozen) = e.frozen_q.head(frozen);
  }
  for (int i = 0; i < frozen; ++i) out.held[static_cast<std::size_t>(i)] = true;
  return frozen;
}

}  // namespace pneumatic_finger
