// An obstacle in the finger's bending plane: the section of a grasp object by that plane (object_section.hpp), against
// which the contact rule (contact.hpp) measures the backbone's segments. ROS-free.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

namespace pneumatic_finger {

/// A convex region of the finger's plane: a disk (the section of a sphere or of a cylinder across its axis), a convex
/// polygon (of a box), or an ellipse (of a cylinder cut at a slant).
class Obstacle {
 public:
  static Obstacle disk(double x_m, double y_m, double radius_m);
  /// @param vertices_m the corners in order (either direction); must be convex, at least 3.
  static Obstacle polygon(const std::vector<Eigen::Vector2d>& vertices_m);
  /// @param angle_rad the direction of the @p a_m semi-axis from +x.
  static Obstacle ellipse(double x_m, double y_m, double a_m, double b_m, double angle_rad);

  /// How far the segment @p p -> @p q is from the region: > 0 apart (for a disk the distance, otherwise a
  /// continuous quantity that is 0 exactly when they touch), <= 0 touching or overlapping.
  double clearance(const Eigen::Vector2d& p, const Eigen::Vector2d& q) const;

  /// The point of the segment p -> q nearest the region (the contact point when they touch).
  Eigen::Vector2d nearestPoint(const Eigen::Vector2d& p, const Eigen::Vector2d& q) const;

  /// Radius of a disk around the origin that contains the region's nearest point: the region is out of reach of
  /// a finger of length L when distanceFromOrigin() > L.
  double distanceFromOrigin() const;

  /// For a disk: its centre and radius, and true; false for the other shapes.
  bool asDisk(Eigen::Vector2d& center_m, double& radius_m) const {
    center_m = center_;
    radius_m = radius_;
    return kind_ == Kind::kDisk;
  }

  /// Whether the segment @p p -> @p q touches or enters the region (clearance <= 0, without the square root for a
  /// disk).
  bool touches(const Eigen::Vector2d& p, const Eigen::Vector2d& q) const;

  /// Whether @p p lies inside the region or on its boundary.
  bool contains(const Eigen::Vector2d& p) const { return clearance(p, p) <= 0; }

  /// Why the obstacle is not valid (not finite, radius <= 0, polygon not convex), empty when it is.
  std::string problem() const;

 private:
  /// An ellipse's frame, scaled to the unit circle: touching is preserved (an affine map), and so is a segment's t.
  Eigen::Vector2d toUnit(const Eigen::Vector2d& v) const;

  enum class Kind { kDisk, kPolygon, kEllipse } kind_ = Kind::kDisk;
  Eigen::Vector2d center_ = Eigen::Vector2d::Zero();
  double radius_ = 0.0, a_ = 0.0, b_ = 0.0, cos_ = 1.0, sin_ = 0.0;
  std::vector<Eigen::Vector2d> vertices_;
};

}  // namespace pneumatic_finger
