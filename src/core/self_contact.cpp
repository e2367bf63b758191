// Where the finger meets itself (self_contact.hpp).
#include "pneumatic_finger/core/self_contact.hpp"

#include <cmath>

#include "pneumatic_finger/core/units.hpp"

namespace pneumatic_finger {

namespace {

// The sign of the turn a -> b -> c: +1 left, -1 right, 0 in line.
int turn(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double cross = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
  return (cross > 0) - (cross < 0);
}

// c, in line with a and b, lies within their box.
bool within(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return std::fmin(a.x(), b.x()) <= c.x() && c.x() <= std::fmax(a.x(), b.x()) && std::fmin(a.y(), b.y()) <= c.y() &&
         c.y() <= std::fmax(a.y(), b.y());
}

// Segments pq and rs meet (cross, or touch end to side, or overlap in line).
bool segmentsMeet(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r,
                  const Eigen::Vector2d& s) {
  const int d1 = turn(r, s, p), d2 = turn(r, s, q), d3 = turn(p, q, r), d4 = turn(p, q, s);
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;
  return (d1 == 0 && within(r, s, p)) || (d2 == 0 && within(r, s, q)) || (d3 == 0 && within(p, q, r)) ||
         (d4 == 0 && within(p, q, s));
}

}  // namespace

bool backboneMeetsItself(const Eigen::Ref<const Eigen::Matrix2Xd>& backbone_m, const double* joint_angle_rad) {
  const Eigen::Index points = backbone_m.cols();
  double turning_rad = 0.0;
  for (Eigen::Index i = 0; i + 2 < points; ++i) turning_rad += std::fabs(joint_angle_rad[i]);
  if (!(turning_rad > kPi)) return false;
  for (Eigen::Index i = 0; i + 1 < points; ++i) {
    for (Eigen::Index j = i + 2; j + 1 < points; ++j) {
      if (segmentsMeet(backbone_m.col(i), backbone_m.col(i + 1), backbone_m.col(j), backbone_m.col(j + 1))) return true;
    }
  }
  return false;
}

bool jointsMeetThemselves(const FingerParameters& parameters, const double* joint_angle_rad) {
  const int n = parameters.chamber_count;
  double turning_rad = 0.0;
  for (int i = 0; i < n; ++i) turning_rad += std::fabs(joint_angle_rad[i]);
  if (!(turning_rad > kPi)) return false;  // no loop: the backbone is not built
  Eigen::Matrix2Xd points(2, n + 2);
  points.col(0).setZero();
  points.col(1) = Eigen::Vector2d(parameters.base_segment_length_m, 0.0);
  double direction_rad = 0.0;
  for (int i = 0; i < n; ++i) {  // eq 38: the direction turns by q_i at joint i, then segment i runs Z_i along it
    direction_rad += joint_angle_rad[i];
    const double z = parameters.segment_length_m[static_cast<std::size_t>(i)];
    points.col(i + 2) = points.col(i + 1) + z * Eigen::Vector2d(std::cos(direction_rad), std::sin(direction_rad));
  }
  return backboneMeetsItself(points, joint_angle_rad);
}

std::string selfContactMessage(double tip_angle_rad) {
  return "the finger meets itself (tip angle " + formatMessage(tip_angle_rad) +
         " rad): its backbone crosses itself, where the model, which has no self-contact, passes through the finger";
}

}  // namespace pneumatic_finger
