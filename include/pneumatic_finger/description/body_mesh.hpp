// The drawn body as a mesh (docs/DRAWING.md, "The body as a mesh"): the box of elastomer with its cavities, from the
// drawing, as a closed triangle mesh a designer can look at and a CAD tool can open (STL).
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "pneumatic_finger/core/drawing.hpp"

namespace pneumatic_finger {

/// One triangle, its corners counter-clockwise seen from outside the solid (its normal points out of the elastomer;
/// into a cavity for a cavity's faces).
struct MeshTriangle {
  Eigen::Vector3d a, b, c;
};

/// The body of @p drawing in the finger's frame (m): x along the finger from the mount (the base's start), y across
/// (the body centred on it), z up from the bending axis (the strain-limiting layer's top; the layer below it). The
/// outer box (base, end walls, cavities and walls along; body_width_m across; from -layer_thickness_m up to the roof's
/// top) and each cavity as its own closed inner shell (the inlet channel between cavities is not drawn).
/// @throws ParameterError naming the key to give where a cavity would open onto the body's bottom face (its floor at
/// or below the layer's bottom: give drawing/layer_thickness_m or drawing/floor_height_m), and for split walls
/// (gap_m > 0), which the mesh does not draw yet
std::vector<MeshTriangle> drawnBodyMesh(const ActuatorDrawing& drawing);

/// The volume the mesh encloses (m^3), by the divergence theorem: the sum of each triangle's signed tetrahedron with
/// the origin.
double meshVolume(const std::vector<MeshTriangle>& mesh);

/// ASCII STL of @p mesh, named @p name, in metres (as URDF meshes are; a CAD tool asks for the unit on import), each
/// coordinate with 17 significant digits (the mesh's doubles, read back exactly).
std::string meshToStl(const std::vector<MeshTriangle>& mesh, const std::string& name);

}  // namespace pneumatic_finger
