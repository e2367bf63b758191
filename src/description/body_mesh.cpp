// The drawn body as a mesh (body_mesh.hpp).
#include "pneumatic_finger/description/body_mesh.hpp"

#include <Eigen/Geometry>

#include <cstdio>
#include <sstream>

#include "pneumatic_finger/core/parameters.hpp"

namespace pneumatic_finger {

namespace {

// The 12 triangles of the box [lo, hi], facing out of it (@p outward) or into it (a cavity's shell).
void addBox(std::vector<MeshTriangle>& mesh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, bool outward) {
  const auto corner = [&](int i) {  // bit 0: x, bit 1: y, bit 2: z
    return Eigen::Vector3d(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  };
  // Each face's corners counter-clockwise seen from outside the box.
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    const Eigen::Vector3d p0 = corner(f[0]), p1 = corner(f[1]), p2 = corner(f[2]), p3 = corner(f[3]);
    if (outward) {
      mesh.push_back({p0, p1, p2});
      mesh.push_back({p0, p2, p3});
    } else {
      mesh.push_back({p0, p2, p1});
      mesh.push_back({p0, p3, p2});
    }
  }
}

std::string mm(double m) { return formatMessage(1e3 * m) + " mm"; }

}  // namespace

std::vector<MeshTriangle> drawnBodyMesh(const ActuatorDrawing& d) {
  if (d.gap_m > 0.0) {
    throw ParameterError("drawing/gap_m = " + mm(d.gap_m) + ": the body's mesh does not draw split walls yet");
  }
  if (!(d.floor_height_m > -d.layer_thickness_m)) {
    throw ParameterError("the cavities' floor (" + mm(d.floor_height_m) + " above the bending axis) is the body's "
                         "bottom face (the strain-limiting layer is " + mm(d.layer_thickness_m) + " thick): give "
                         "drawing/layer_thickness_m, the layer under the body (--set drawing/layer_thickness_m=0.002, "
                         "or under drawing: in the file), or drawing/floor_height_m, so that the mesh closes the "
                         "cavities");
  }
  const int n = d.chamber_count;
  const double length = bodyLengthM(d), half_width = 0.5 * d.body_width_m, top = bodyTopM(d);
  std::vector<MeshTriangle> mesh;
  addBox(mesh, {0.0, -half_width, -d.layer_thickness_m}, {length, half_width, top}, true);
  for (int k = 0; k < n; ++k) {
    const double x0 = d.base_length_m + d.end_wall_thickness_m + k * (d.cavity_length_m + d.wall_thickness_m);
    addBox(mesh, {x0, -0.5 * d.cavity_width_m, d.floor_height_m},
           {x0 + d.cavity_length_m, 0.5 * d.cavity_width_m, d.floor_height_m + d.cavity_height_m}, false);
  }
  return mesh;
}

double meshVolume(const std::vector<MeshTriangle>& mesh) {
  double six_v = 0.0;
  for (const MeshTriangle& t : mesh) six_v += t.a.dot(t.b.cross(t.c));
  return six_v / 6.0;
}

std::string meshToStl(const std::vector<MeshTriangle>& mesh, const std::string& name) {
  std::ostringstream out;
  char b[160];
  const auto vertex = [&](const Eigen::Vector3d& p) {
    std::snprintf(b, sizeof b, "      vertex %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
    out << b;
  };
  out << "solid " << name << "\n";
  for (const MeshTriangle& t : mesh) {
    const Eigen::Vector3d normal = (t.b - t.a).cross(t.c - t.a).normalized();
    std::snprintf(b, sizeof b, "  facet normal %.17g %.17g %.17g\n    outer loop\n", normal.x(), normal.y(), normal.z());
    out << b;
    vertex(t.a);
    vertex(t.b);
    vertex(t.c);
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid " << name << "\n";
  return out.str();
}

}  // namespace pneumatic_finger
