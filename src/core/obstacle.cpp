#include "pneumatic_finger/core/obstacle.hpp"

#include <algorithm>
#include <cmath>

namespace pneumatic_finger {

namespace {

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

Eigen::Vector2d Obstacle::toUnit(const Eigen::Vector2d& v) const {
  const Vec d = v - center_;
  return Vec((cos_ * d.x() + sin_ * d.y()) / a_, (-sin_ * d.x() + cos_ * d.y()) / b_);
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

}  // namespace pneumatic_finger
