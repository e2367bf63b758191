#include "pneumatic_finger/core/object_section.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "pneumatic_finger/core/units.hpp"

namespace pneumatic_finger {

namespace {

using Vec2 = Eigen::Vector2d;

// Andrew's monotone chain: the convex hull, counter-clockwise, without repeated or collinear points.
std::vector<Vec2> convexHull(std::vector<Vec2> points) {
  std::sort(points.begin(), points.end(),
            [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  auto turn = [](const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Vec2> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && turn(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

// A hull with (numerically) no area is a point or an edge touching the plane: no section.
std::optional<Obstacle> polygonIfArea(const std::vector<Vec2>& points, double size_m) {
  const std::vector<Vec2> hull = convexHull(points);
  if (hull.size() < 3) return std::nullopt;
  double area2 = 0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Vec2& a = hull[i];
    const Vec2& b = hull[(i + 1) % hull.size()];
    area2 += a.x() * b.y() - a.y() * b.x();
  }
  if (!(area2 > 1e-12 * size_m * size_m)) return std::nullopt;
  return Obstacle::polygon(hull);
}

std::optional<Obstacle> boxSection(const SolidObject& s) {
  // The section of a convex polyhedron by a plane is the convex hull of where its edges cross the plane (and of
  // the vertices on it).
  std::array<Eigen::Vector3d, 8> v;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d corner(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
    v[static_cast<std::size_t>(i)] = s.pose * corner.cwiseProduct(s.box_size_m);
  }
  std::vector<Vec2> points;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d& a = v[static_cast<std::size_t>(i)];
    if (a.z() == 0) points.emplace_back(a.x(), a.y());
    for (int bit = 1; bit < 8; bit <<= 1) {
      if (i & bit) continue;  // each edge once, from its vertex with the bit clear
      const Eigen::Vector3d& b = v[static_cast<std::size_t>(i | bit)];
      if ((a.z() < 0 && b.z() > 0) || (a.z() > 0 && b.z() < 0)) {
        const double t = a.z() / (a.z() - b.z());
        points.emplace_back(a.x() + t * (b.x() - a.x()), a.y() + t * (b.y() - a.y()));
      }
    }
  }
  return polygonIfArea(points, s.box_size_m.maxCoeff());
}

std::optional<Obstacle> cylinderSection(const SolidObject& s, SectionAccuracy& accuracy) {
  const Eigen::Vector3d c = s.pose.translation();
  const Eigen::Vector3d axis = s.pose.linear().col(2).normalized();
  const double r = s.radius_m, half_h = 0.5 * s.height_m;
  const Vec2 axis_in_plane(axis.x(), axis.y());
  const double along = axis_in_plane.norm();  // sin of the axis' angle from the plane normal
  if (std::fabs(axis.z()) < 1e-12) {
    // The axis parallel to the plane, |c_z| from it: a rectangle 2 sqrt(r^2 - c_z^2) wide and as long as the
    // cylinder.
    if (!(std::fabs(c.z()) < r)) return std::nullopt;
    const double w = std::sqrt(r * r - c.z() * c.z());
    const Vec2 u = axis_in_plane / along, n(-u.y(), u.x()), m(c.x(), c.y());
    return polygonIfArea({m + half_h * u + w * n, m - half_h * u + w * n, m - half_h * u - w * n,
                          m + half_h * u - w * n},
                         std::max(r, half_h));
  }
  // Otherwise the plane cuts the infinite cylinder in an ellipse centred where the axis crosses it: semi-axes
  // r / |a_z| along the axis' projection and r across it. Along the ellipse the axial coordinate is
  // s(phi) = s_0 + r tan(tilt) cos(phi), with s_0 the centre's; the caps keep |s| <= h/2.
  const double t0 = -c.z() / axis.z();  // axial coordinate of the centre
  const Vec2 centre = Vec2(c.x(), c.y()) + t0 * axis_in_plane;
  const double major = r / std::fabs(axis.z());
  const double reach = r * along / std::fabs(axis.z());  // r tan(tilt): how far s swings along the ellipse
  if (std::fabs(t0) + reach <= half_h) {
    if (along == 0) return Obstacle::disk(centre.x(), centre.y(), r);
    return Obstacle::ellipse(centre.x(), centre.y(), major, r, std::atan2(axis_in_plane.y(), axis_in_plane.x()));
  }
  // Through a cap: the ellipse's arcs with |s| <= h/2, joined by the caps' chords. cos(phi) must lie in [lo, hi].
  if (!(reach > 0)) return std::nullopt;  // the plane lies beyond both caps
  const double lo = std::max(-1.0, (-half_h - t0) / reach), hi = std::min(1.0, (half_h - t0) / reach);
  if (!(lo < hi)) return std::nullopt;
  accuracy = SectionAccuracy::kPolygonized;
  const Vec2 u = axis_in_plane / along, n(-u.y(), u.x());
  const double phi_a = std::acos(hi), phi_b = std::acos(lo);  // 0 <= phi_a < phi_b <= pi
  std::vector<Vec2> points;
  points.reserve(2 * (kSectionArcSamples + 1));
  for (int sign : {1, -1}) {
    for (int i = 0; i <= kSectionArcSamples; ++i) {
      const double phi = phi_a + (phi_b - phi_a) * i / kSectionArcSamples;
      points.push_back(centre + major * std::cos(phi) * u + sign * r * std::sin(phi) * n);
    }
  }
  return polygonIfArea(points, std::max(r, half_h));
}

}  // namespace

std::string SolidObject::problem() const {
  if (!pose.matrix().allFinite()) return "the pose is not finite";
  const Eigen::Matrix3d rtr = pose.linear().transpose() * pose.linear();
  if (!rtr.isIdentity(1e-9)) return "the pose's rotation is not a rotation (its orientation quaternion is not unit)";
  switch (shape) {
    case Shape::kBox:
      if (!box_size_m.allFinite() || !(box_size_m.minCoeff() > 0)) return "a box's three sizes must be finite and > 0";
      return "";
    case Shape::kSphere:
      if (!std::isfinite(radius_m) || !(radius_m > 0)) return "a sphere's radius must be finite and > 0";
      return "";
    case Shape::kCylinder:
      if (!std::isfinite(radius_m) || !(radius_m > 0) || !std::isfinite(height_m) || !(height_m > 0)) {
        return "a cylinder's height and radius must be finite and > 0";
      }
      return "";
  }
  return "unknown shape";
}

double SolidObject::boundingRadius() const {
  switch (shape) {
    case Shape::kBox:
      return 0.5 * box_size_m.norm();
    case Shape::kSphere:
      return radius_m;
    case Shape::kCylinder:
      return std::hypot(radius_m, 0.5 * height_m);
  }
  return 0.0;
}

std::optional<Obstacle> sectionByFingerPlane(const SolidObject& solid, SectionAccuracy* accuracy) {
  SectionAccuracy a = SectionAccuracy::kExact;
  std::optional<Obstacle> out;
  switch (solid.shape) {
    case SolidObject::Shape::kSphere: {
      const Eigen::Vector3d c = solid.pose.translation();
      if (std::fabs(c.z()) < solid.radius_m) {
        out = Obstacle::disk(c.x(), c.y(), std::sqrt(solid.radius_m * solid.radius_m - c.z() * c.z()));
      }
      break;
    }
    case SolidObject::Shape::kBox:
      out = boxSection(solid);
      break;
    case SolidObject::Shape::kCylinder:
      out = cylinderSection(solid, a);
      break;
  }
  if (accuracy) *accuracy = a;
  return out;
}

}  // namespace pneumatic_finger
