// A solid object (box, sphere or cylinder, the shapes of shape_msgs/SolidPrimitive) cut by the finger's bending
// plane: the section is the planar obstacle the contact rule works on (docs/GRASP.md). ROS-free.
#pragma once

#include <Eigen/Geometry>

#include <optional>
#include <string>

#include "pneumatic_finger/core/contact.hpp"

namespace pneumatic_finger {

/// A solid in the finger's frame (<prefix>segment_0: x along the unbent finger, y toward the strain-limited side,
/// z normal to the bending plane). Dimensions follow shape_msgs/SolidPrimitive: a box's edges along its own x, y,
/// z; a sphere's radius; a cylinder's height along its own z and its radius.
struct SolidObject {
  enum class Shape { kBox, kSphere, kCylinder };
  Shape shape = Shape::kSphere;
  Eigen::Vector3d box_size_m = Eigen::Vector3d::Zero();  ///< box: edge lengths (m)
  double radius_m = 0.0;                                 ///< sphere, cylinder (m)
  double height_m = 0.0;                                 ///< cylinder (m)
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< the solid's centre and axes in the finger frame

  /// Why the solid is not valid (a size not finite or <= 0, a pose not finite), empty when it is.
  std::string problem() const;
  /// Radius of the smallest sphere about the solid's centre that contains it (m).
  double boundingRadius() const;
};

/// How exactly a section represents the solid's.
enum class SectionAccuracy {
  kExact,        ///< disk, ellipse or polygon equal to the section
  kPolygonized,  ///< a cylinder cut at a slant through an end cap: an inscribed polygon of kSectionArcSamples chords per arc
};

/// Chords per arc of a polygonized section. It lies inside the true one by at most r (1 - cos(dphi / 2)) with dphi
/// at most pi / 256 in the ellipse's parameter: below 2e-5 of the major semi-axis (0.3 um for a 16 mm cylinder
/// tilted 0..60 degrees).
constexpr int kSectionArcSamples = 256;

/// The solid's section by the plane z = 0 of its frame, as an obstacle of the contact rule; nothing when the plane
/// misses the solid or only grazes it (a section of zero area: a point, an edge, a face seen edge-on).
std::optional<Obstacle> sectionByFingerPlane(const SolidObject& solid, SectionAccuracy* accuracy = nullptr);

}  // namespace pneumatic_finger
