#include "pneumatic_finger/core/contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "pneumatic_finger/core/units.hpp"
#include "simd_math.hpp"

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

double cross(const Vec& a, const Vec& b) { return a.x() * b.y() - a.y() * b.x(); }

// Parameter t in [0, 1] of the point of segment p -> q nearest to c.
double nearestT(const Vec& p, const Vec& q, const Vec& c) {
  const Vec d = q - p;
  const double len2 = d.squaredNorm();
  if (!(len2 > 0)) return 0.0;
  return std::clamp((c - p).dot(d) / len2, 0.0, 1.0);
}

double pointSegmentDistance(const Vec& c, const Vec& p, const Vec& q) {
  return (p + nearestT(p, q, c) * (q - p) - c).norm();
}

bool segmentsCross(const Vec& a, const Vec& b, const Vec& c, const Vec& d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a), d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}

double segmentSegmentDistance(const Vec& a, const Vec& b, const Vec& c, const Vec& d) {
  if (segmentsCross(a, b, c, d)) return 0.0;
  return std::min({pointSegmentDistance(a, c, d), pointSegmentDistance(b, c, d), pointSegmentDistance(c, a, b),
                   pointSegmentDistance(d, a, b)});
}

}  // namespace

Obstacle Obstacle::disk(double x_m, double y_m, double radius_m) {
  Obstacle o;
  o.kind_ = Kind::kDisk;
  o.center_ = Vec(x_m, y_m);
  o.radius_ = radius_m;
  return o;
}

Obstacle Obstacle::polygon(const std::vector<Eigen::Vector2d>& vertices_m) {
  Obstacle o;
  o.kind_ = Kind::kPolygon;
  o.vertices_ = vertices_m;
  // Counter-clockwise, so that "inside" is to the left of every edge.
  double area = 0;
  for (std::size_t i = 0; i < o.vertices_.size(); ++i) {
    area += cross(o.vertices_[i], o.vertices_[(i + 1) % o.vertices_.size()]);
  }
  if (area < 0) std::reverse(o.vertices_.begin(), o.vertices_.end());
  return o;
}

Obstacle Obstacle::ellipse(double x_m, double y_m, double a_m, double b_m, double angle_rad) {
  Obstacle o;
  o.kind_ = Kind::kEllipse;
  o.center_ = Vec(x_m, y_m);
  o.a_ = a_m;
  o.b_ = b_m;
  o.cos_ = std::cos(angle_rad);
  o.sin_ = std::sin(angle_rad);
  return o;
}

std::string Obstacle::problem() const {
  switch (kind_) {
    case Kind::kDisk:
      if (!center_.allFinite() || !std::isfinite(radius_)) return "the disk's centre and radius must be finite";
      if (!(radius_ > 0)) return "the disk's radius must be > 0";
      return "";
    case Kind::kEllipse:
      if (!center_.allFinite() || !std::isfinite(a_) || !std::isfinite(b_) || !std::isfinite(cos_)) {
        return "the ellipse's centre, semi-axes and angle must be finite";
      }
      if (!(a_ > 0 && b_ > 0)) return "the ellipse's semi-axes must be > 0";
      return "";
    case Kind::kPolygon: {
      if (vertices_.size() < 3) return "a polygon needs at least 3 vertices";
      for (const Vec& v : vertices_) {
        if (!v.allFinite()) return "the polygon's vertices must be finite";
      }
      for (std::size_t i = 0; i < vertices_.size(); ++i) {
        const Vec& a = vertices_[i];
        const Vec& b = vertices_[(i + 1) % vertices_.size()];
        const Vec& c = vertices_[(i + 2) % vertices_.size()];
        if (!(cross(b - a, c - b) > 0)) return "the polygon must be convex, with no repeated or collinear vertices";
      }
      return "";
    }
  }
  return "";
}

double Obstacle::clearance(const Eigen::Vector2d& p, const Eigen::Vector2d& q) const {
  switch (kind_) {
    case Kind::kDisk:
      return pointSegmentDistance(center_, p, q) - radius_;
    case Kind::kEllipse: {
      // In the ellipse's own frame scaled to the unit circle, touching is preserved (an affine map); the distance
      // there, scaled back by the smaller semi-axis, is 0 exactly at touching and continuous on either side.
      auto toUnit = [this](const Vec& v) {
        const Vec d = v - center_;
        return Vec((cos_ * d.x() + sin_ * d.y()) / a_, (-sin_ * d.x() + cos_ * d.y()) / b_);
      };
      return (pointSegmentDistance(Vec::Zero(), toUnit(p), toUnit(q)) - 1.0) * std::min(a_, b_);
    }
    case Kind::kPolygon: {
      const std::size_t n = vertices_.size();
      auto inside = [this, n](const Vec& v) {
        double depth = INFINITY;
        for (std::size_t i = 0; i < n; ++i) {
          const Vec& a = vertices_[i];
          const Vec edge = vertices_[(i + 1) % n] - a;
          const double s = cross(edge, v - a) / edge.norm();  // distance to the left of the edge's line
          if (!(s > 0)) return 0.0;
          depth = std::min(depth, s);
        }
        return depth;
      };
      const double depth = std::max(inside(p), inside(q));
      if (depth > 0) return -depth;
      double d = INFINITY;
      for (std::size_t i = 0; i < n; ++i) d = std::min(d, segmentSegmentDistance(p, q, vertices_[i], vertices_[(i + 1) % n]));
      return d;
    }
  }
  return INFINITY;
}

bool Obstacle::touches(const Eigen::Vector2d& p, const Eigen::Vector2d& q) const {
  if (kind_ != Kind::kDisk) return clearance(p, q) <= 0;
  return (p + nearestT(p, q, center_) * (q - p) - center_).squaredNorm() <= radius_ * radius_;
}

Eigen::Vector2d Obstacle::nearestPoint(const Eigen::Vector2d& p, const Eigen::Vector2d& q) const {
  switch (kind_) {
    case Kind::kDisk:
      return p + nearestT(p, q, center_) * (q - p);
    case Kind::kEllipse: {
      auto toUnit = [this](const Vec& v) {
        const Vec d = v - center_;
        return Vec((cos_ * d.x() + sin_ * d.y()) / a_, (-sin_ * d.x() + cos_ * d.y()) / b_);
      };
      return p + nearestT(toUnit(p), toUnit(q), Vec::Zero()) * (q - p);  // an affine map keeps t
    }
    case Kind::kPolygon: {
      // Among the segment's ends and the feet of the polygon's corners, the one nearest the polygon.
      std::vector<Vec> candidates = {p, q};
      for (const Vec& v : vertices_) candidates.push_back(p + nearestT(p, q, v) * (q - p));
      Vec best = p;
      double best_d = INFINITY;
      for (const Vec& c : candidates) {
        const double d = clearance(c, c);
        if (d < best_d) best_d = d, best = c;
      }
      return best;
    }
  }
  return p;
}

double Obstacle::distanceFromOrigin() const {
  switch (kind_) {
    case Kind::kDisk:
      return center_.norm() - radius_;
    case Kind::kEllipse:
      return center_.norm() - std::max(a_, b_);  // a lower bound
    case Kind::kPolygon: {
      const double c = clearance(Vec::Zero(), Vec::Zero());
      return std::max(c, 0.0);
    }
  }
  return 0.0;
}

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
  points.col(0) = Vec::Zero();
  points.col(1) = Vec(p.base_segment_length_m, 0.0);
  // The direction turns by q_i at joint i: a rotation, composed; a joint whose angle equals the previous one's (the
  // free joints of identical chambers, a frozen run) reuses its sine and cosine.
  double dir_c = 1.0, dir_s = 0.0, rot_c = 1.0, rot_s = 0.0;
  for (int i = 0; i < n; ++i) {
    if (i == 0 || q[i] != q[i - 1]) {
      cosSin(q[i], rot_c, rot_s);
    }
    const double c = dir_c * rot_c - dir_s * rot_s;
    dir_s = dir_s * rot_c + dir_c * rot_s;
    dir_c = c;
    const double z = p.segment_length_m[static_cast<std::size_t>(i)];
    points.col(i + 2) = points.col(i + 1) + z * Vec(dir_c, dir_s);
  }
}

ContactSolver::Event ContactSolver::findEvent(const Obstacle& obstacle, double from, int frozen,
                                              const JointAngles& frozen_q, double u_end, double& u_clear) const {
  const int n = model_.chamberCount();
  Event event;
  JointAngles q(n);
  BackbonePoints points(2, n + 2);
  // Joints 1..frozen are held at frozen_q; the others follow q(p). Segment k (O_k -> O_k+1) moves with joints 1..k,
  // so the segments that can still move are frozen+1..N.
  auto configure = [&](double p) {
    if (!model_.jointAnglesAt(p, q.data())) return false;
    q.head(frozen) = frozen_q.head(frozen);
    backbone(q, points);
    return true;
  };
  // The smallest clearance of the moving segments at pressure p, and which segment has it.
  auto clearanceAt = [&](double p, int& segment) {
    if (!configure(p)) return -std::numeric_limits<double>::infinity();
    double c = INFINITY;
    for (int k = frozen + 1; k <= n; ++k) {
      const double ck = obstacle.clearance(points.col(k), points.col(k + 1));
      if (ck < c) c = ck, segment = k;
    }
    return c;
  };
  // Brackets on a fixed grid in sqrt(p) (the angles grow like it), the same whatever pressure is asked for: the touch
  // pressures, and so the frozen angles, then do not depend on the target pressure, and no joint moves back as the
  // pressure rises. The grid runs one step past the target when needed, so a bracket is never cut short.
  constexpr double kGridStep = 10.0;    // sqrt(Pa): 45 brackets up to 2 kg/cm^2
  constexpr double kTouchM = 1e-12;     // segments this close at the touch are touching it too
  const double u0 = std::sqrt(from);
  double lo = -1.0, hi = -1.0;
  int seg = 0;
  std::array<double, 3> c{INFINITY, INFINITY, clearanceAt(from, seg)};  // the last three samples
  for (int j = 1; lo < 0; ++j) {
    const double u_prev = u0 + (j - 1) * kGridStep, u = u0 + j * kGridStep;
    c = {c[1], c[2], clearanceAt(u * u, seg)};
    if (c[2] <= 0) {
      lo = u_prev * u_prev;
      hi = u * u;
      break;
    }
    // A grazing touch between two samples: a local minimum of the clearance, searched by golden sections; it
    // counts when it reaches the touch distance.
    if (j >= 2 && c[1] < c[0] && c[1] < c[2]) {
      double a = u - 2 * kGridStep, b = u;
      for (int it = 0; it < 200 && b - a > 1e-16 * b; ++it) {
        const double m1 = b - 0.6180339887498949 * (b - a), m2 = a + 0.6180339887498949 * (b - a);
        int s1 = 0, s2 = 0;
        if (clearanceAt(m1 * m1, s1) < clearanceAt(m2 * m2, s2)) {
          b = m2;
        } else {
          a = m1;
        }
      }
      const double u_min = 0.5 * (a + b);
      if (clearanceAt(u_min * u_min, seg) <= kTouchM) {
        lo = hi = u_min * u_min;
        break;
      }
    }
    if (u >= u_end) {  // clear up to (and past) the pressure asked for
      u_clear = u;
      return event;
    }
  }
  // Bisection on the touch condition: lo clear, hi touching, until the pressures agree to the last digits.
  for (int it = 0; it < 200 && hi - lo > kRelativePressureTolerance * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (clearanceAt(mid, seg) <= 0 ? hi : lo) = mid;
  }
  // Freeze at lo, the last shape clear of the obstacle: no joint passes its free angle, nothing penetrates.
  const double touch_c = clearanceAt(lo, seg);
  event.found = true;
  if (!std::isfinite(touch_c)) {
    event.failed = true;
    return event;
  }
  int m = seg;
  for (int k = frozen + 1; k <= n; ++k) {
    if (obstacle.clearance(points.col(k), points.col(k + 1)) <= touch_c + kTouchM) m = std::max(m, k);
  }
  event.gauge_pa = lo;
  event.frozen = m;
  event.frozen_q = frozen_q;
  event.frozen_q.segment(frozen, m - frozen) = q.segment(frozen, m - frozen);
  event.point_m = obstacle.nearestPoint(points.col(seg), points.col(seg + 1));
  return event;
}

ContactSolver::Event ContactSolver::findEventUniform(const Obstacle& obstacle, double from_half_angle_rad, int frozen,
                                                     const JointAngles& frozen_q, double end_half_angle_rad,
                                                     double& clear_half_angle_rad) const {
  // Identical chambers: every free joint is a function of the one half angle theta (q_1 = (1 + s0) theta, q_n = 2 theta),
  // and the pressure is theta's closed-form inverse. So the search runs in theta, where the backbone costs one
  // sincos and no model solve, and where a point of the backbone moves at most V = sum over free joints of
  // (dq_i/dtheta) x (arc length from joint i to the tip) per radian: a clearance c rules out a touch for the next
  // c / V radians, so far obstacles are passed in a few long steps.
  const FingerParameters& par = model_.parameters();
  const int n = par.chamber_count;
  const double share = par.base_wall_share;  // theta_0 = s0 theta (joint 1)
  Event event;
  // The fixed part: O_{frozen+1} and the direction after joint `frozen` (no trigonometry for the first touch, where
  // nothing is frozen). On the stack: kMaxChamberCount bounds N.
  BackbonePoints points(2, n + 2);
  points.col(0) = Vec::Zero();
  points.col(1) = Vec(par.base_segment_length_m, 0.0);
  double dir0 = 0.0;
  for (int i = 0; i < frozen; ++i) {
    dir0 += frozen_q[i];
    const double z = par.segment_length_m[static_cast<std::size_t>(i)];
    double dir_c, dir_s;
    cosSin(dir0, dir_c, dir_s);
    points.col(i + 2) = points.col(i + 1) + z * Vec(dir_c, dir_s);
  }
  double dir0_c = 1.0, dir0_s = 0.0;
  if (frozen > 0) cosSin(dir0, dir0_c, dir0_s);
  double speed = 0.0;  // V (m/rad)
  {
    double rest = length_m_ - par.base_segment_length_m;  // arc length from joint i (at O_i) to the tip
    for (int i = 1; i <= n; ++i) {
      if (i > frozen) speed += (i == 1 ? 1.0 + share : 2.0) * rest;
      rest -= par.segment_length_m[static_cast<std::size_t>(i - 1)];
    }
  }
  // A disk, the commonest section, is measured in squared distances (one square root per sample, no division:
  // the segments' lengths are fixed).
  Vec disk_center;
  double disk_radius = 0.0;
  const bool disk = obstacle.asDisk(disk_center, disk_radius);
  std::array<double, kMaxChamberCount + 1> inv_length2;  // filled for 1..n below
  for (int k = 1; k <= n; ++k) {
    const double z = par.segment_length_m[static_cast<std::size_t>(k - 1)];
    inv_length2[static_cast<std::size_t>(k)] = 1.0 / (z * z);
  }
  // Places the free segments frozen+1..last at theta and returns the smallest clearance among first..last (and,
  // with per_segment, each one's, indexed by segment).
  std::array<double, kMaxChamberCount + 1> per_segment;
  auto clearanceIn = [&](double theta, int first, int last, int& segment, bool each = false) {
    double c1, s1;
    cosSin(theta, c1, s1);
    const double c2 = (c1 - s1) * (c1 + s1), s2 = 2.0 * s1 * c1;  // e^(2 i theta)
    // e^(i q_1), q_1 = theta_0 + theta; needed only while joint 1 is free.
    double q1_c = c1, q1_s = s1;
    if (share != 0.0 && frozen == 0) {
      const double q1 = share * theta + theta;
      cosSin(q1, q1_c, q1_s);
    }
    double dc = dir0_c, ds = dir0_s;
    double c = INFINITY;
    for (int k = frozen + 1; k <= last; ++k) {
      const double rc = k == 1 ? q1_c : c2, rs = k == 1 ? q1_s : s2;
      const double t = dc * rc - ds * rs;
      ds = ds * rc + dc * rs;
      dc = t;
      const double z = par.segment_length_m[static_cast<std::size_t>(k - 1)];
      points(0, k + 1) = points(0, k) + z * dc;
      points(1, k + 1) = points(1, k) + z * ds;
      if (k < first) continue;
      if (disk) {
        const Vec p = points.col(k), d = points.col(k + 1) - p, w = disk_center - p;
        const double t = std::clamp(w.dot(d) * inv_length2[static_cast<std::size_t>(k)], 0.0, 1.0);
        const double d2 = (w - t * d).squaredNorm();
        if (d2 < c) c = d2, segment = k;
        if (each) per_segment[static_cast<std::size_t>(k)] = std::sqrt(d2) - disk_radius;
      } else {
        const double ck = obstacle.clearance(points.col(k), points.col(k + 1));
        if (ck < c) c = ck, segment = k;
        if (each) per_segment[static_cast<std::size_t>(k)] = ck;
      }
    }
    return disk ? std::sqrt(c) - disk_radius : c;
  };
  auto clearanceAt = [&](double theta, int& segment) { return clearanceIn(theta, frozen + 1, n, segment); };
  constexpr double kGridStep = 1e-3;  // rad of theta: the finest spacing of the bracketing samples
  constexpr double kTouchM = 1e-12;   // segments this close at the touch are touching it too
  const double t0 = from_half_angle_rad;
  int seg = 0;
  // The samples lie on the grid t0 + j kGridStep; far from the obstacle whole runs of it are skipped, as the bound
  // allows (never past a point where the clearance could have come within kTouchM). The sequence depends on the
  // obstacle and the start alone, not on the end asked for: the touch found is the same whatever the end.
  std::array<double, 3> s{t0, t0, t0};
  std::array<double, 3> c{INFINITY, INFINITY, clearanceAt(t0, seg)};
  double lo = -1.0, hi = -1.0;
  for (long j = 0;;) {
    // Never beyond theta = 1.5 rad: the model's range ends before pi/2, and the skips must not depend on the end.
    const double allowed = std::min((c[2] - kTouchM) / speed, 1.5 - (t0 + static_cast<double>(j) * kGridStep));
    j += std::max(1L, static_cast<long>(std::floor(allowed / kGridStep)));
    const double t = t0 + static_cast<double>(j) * kGridStep;
    s = {s[1], s[2], t};
    c = {c[1], c[2], clearanceAt(t, seg)};
    if (c[2] <= 0) {
      lo = s[1];
      hi = t;
      break;
    }
    // A local minimum between samples: a grazing approach. Golden sections find it, stopping as soon as the bound
    // proves it stays clear of kTouchM; it counts as a touch when it reaches kTouchM.
    if (c[1] < c[0] && c[1] < c[2]) {
      double a = s[0], b = s[2];
      double m1 = b - 0.6180339887498949 * (b - a), m2 = a + 0.6180339887498949 * (b - a);
      int s1 = 0, s2 = 0;
      double f1 = clearanceAt(m1, s1), f2 = clearanceAt(m2, s2);
      for (int it = 0; it < 200 && b - a > 1e-16 * b && std::min(f1, f2) - speed * (b - a) <= kTouchM; ++it) {
        if (f1 < f2) {
          b = m2, m2 = m1, f2 = f1;
          m1 = b - 0.6180339887498949 * (b - a);
          f1 = clearanceAt(m1, s1);
        } else {
          a = m1, m1 = m2, f1 = f2;
          m2 = a + 0.6180339887498949 * (b - a);
          f2 = clearanceAt(m2, s2);
        }
      }
      const double t_min = f1 < f2 ? m1 : m2;
      if (std::min(f1, f2) <= kTouchM) {
        lo = hi = t_min;
        break;
      }
    }
    if (t >= end_half_angle_rad) {  // clear up to (and past) the end asked for
      clear_half_angle_rad = t;
      return event;
    }
  }
  // The touch: lo clear, hi touching, to kRelativeHalfAngleTolerance, by regula falsi with the Illinois correction
  // (the clearance is smooth near a touch, so a few steps do), falling back to bisection when a step leaves the
  // bracket.
  if (hi > lo) {
    // Only the segments that can come within reach inside the bracket (by the bound) are measured there: usually
    // one or two.
    int first = n, last = frozen + 1;
    double f_lo = clearanceIn(lo, frozen + 1, n, seg, true);
    for (int k = frozen + 1; k <= n; ++k) {
      if (per_segment[static_cast<std::size_t>(k)] - speed * (hi - lo) <= kTouchM) {
        first = std::min(first, k);
        last = std::max(last, k);
      }
    }
    first = std::min(first, last);
    double f_hi = clearanceIn(hi, first, last, seg);
    int side = 0;
    for (int it = 0; it < 200 && hi - lo > kRelativeHalfAngleTolerance * hi; ++it) {
      double mid = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
      if (!(mid > lo && mid < hi)) mid = 0.5 * (lo + hi);
      const double f = clearanceIn(mid, first, last, seg);
      if (f <= 0) {
        hi = mid, f_hi = f;
        if (side == -1) f_lo *= 0.5;  // the same end kept twice: halve its weight, or the secant crawls
        side = -1;
      } else {
        lo = mid, f_lo = f;
        if (side == 1) f_hi *= 0.5;
        side = 1;
      }
    }
  }
  // Freeze at lo, the last shape clear of the obstacle: no joint passes its free angle, nothing penetrates.
  const double touch_c = clearanceIn(lo, frozen + 1, n, seg, true);
  event.found = true;
  double gauge = 0.0;
  if (!std::isfinite(touch_c) || !model_.gaugeForHalfAngle(lo, gauge)) {
    event.failed = true;
    return event;
  }
  // Segments as close as the touching one (to kTouchM) touch too: a touch at a joint holds both of its segments.
  int m = seg;
  for (int k = seg + 1; k <= n; ++k) {
    if (per_segment[static_cast<std::size_t>(k)] <= touch_c + kTouchM) m = k;
  }
  event.gauge_pa = gauge;
  event.half_angle_rad = lo;
  event.frozen = m;
  event.frozen_q = frozen_q;
  // The held angles, as the model writes them: q_1 = theta_0 + theta (jointAnglesAt), q_n = 2 theta.
  for (int i = frozen; i < m; ++i) event.frozen_q[i] = i == 0 ? share * lo + lo : 2.0 * lo;
  event.point_m = obstacle.nearestPoint(points.col(seg), points.col(seg + 1));
  return event;
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
  const double pressure = std::max(gauge_pa, 0.0);
  out.joint_angle_rad.resize(n);  // the free angles first; the held ones are written over them below
  double free_half_angle_rad = 0.0;  // theta_1, the half angle of chamber 1's walls (all of them, identical chambers)
  std::array<double, kMaxChamberCount> half;
  if (!model.jointAnglesAt(pressure, out.joint_angle_rad.data(), half.data())) {
    out.status = ContactState::Status::kSolverFailure;
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
  // The touch events do not depend on the pressure asked for: they are found once, in order, and kept. A pressure
  // within what is already known costs only the free model and the backbone.
  while (!failed_ && (events_.empty() || events_.back().gauge_pa <= pressure) && frozen_ < n &&
         pressure > clear_gauge_pa_) {
    ContactSolver::Event e;
    double clear_gauge_pa = pressure;
    if (solver_.uniform_) {
      // The end in half angle: the free walls' half angle at the pressure.
      const double from = events_.empty() ? 0.0 : events_.back().half_angle_rad;
      double clear = 0.0, gauge = 0.0;
      e = solver_.findEventUniform(obstacle_, from, frozen_, frozen_q_, free_half_angle_rad, clear);
      if (!e.found && solver_.model_.gaugeForHalfAngle(clear, gauge)) clear_gauge_pa = std::max(gauge, pressure);
    } else {
      const double from = events_.empty() ? 0.0 : events_.back().gauge_pa;
      double u_clear = 0.0;
      e = solver_.findEvent(obstacle_, from, frozen_, frozen_q_, std::sqrt(pressure), u_clear);
      if (!e.found) clear_gauge_pa = std::max(u_clear * u_clear, pressure);
    }
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
  if (failed_) {
    out.status = ContactState::Status::kSolverFailure;
    solver_.backbone(out.joint_angle_rad, out.backbone_m);
    return out;
  }
  int frozen = 0;
  for (const ContactSolver::Event& e : events_) {
    if (e.gauge_pa > pressure) break;
    if (out.touches == 0) out.first_touch_gauge_pa = e.gauge_pa;
    ++out.touches;
    out.contact_points_m.push_back(e.point_m);
    frozen = e.frozen;
    out.joint_angle_rad.head(frozen) = e.frozen_q.head(frozen);
  }
  for (int i = 0; i < frozen; ++i) out.held[static_cast<std::size_t>(i)] = true;
  solver_.backbone(out.joint_angle_rad, out.backbone_m);
  out.status = frozen > 0 ? ContactState::Status::kInContact : ContactState::Status::kFree;
  return out;
}

}  // namespace pneumatic_finger
