// The drawn body as a mesh (body_mesh.hpp): closed and consistently oriented (every edge met once each way), its
// volume the body's less its cavities, its STL read back to the same corners, and the drawings it cannot close refused.
#include <gtest/gtest.h>

#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "pneumatic_finger/description/body_mesh.hpp"

namespace pf = pneumatic_finger;

namespace {

pf::ActuatorDrawing epflDrawing(double layer_m) {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/epfl_ecoflex30_c7.yaml", raw);
  raw["drawing/layer_thickness_m"] = {{layer_m}, false};
  return *pf::drawingFromRaw(raw);
}

using Point = std::tuple<double, double, double>;
Point key(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

}  // namespace

// Closed and oriented: each directed edge of a triangle appears once, and its reverse once, in another triangle.
TEST(BodyMesh, IsClosedAndOriented) {
  const std::vector<pf::MeshTriangle> mesh = pf::drawnBodyMesh(epflDrawing(0.002));
  ASSERT_EQ(mesh.size(), 12u * 8u);  // the outer box and seven cavities
  std::map<std::pair<Point, Point>, int> edges;
  for (const pf::MeshTriangle& t : mesh) {
    ++edges[{key(t.a), key(t.b)}];
    ++edges[{key(t.b), key(t.c)}];
    ++edges[{key(t.c), key(t.a)}];
  }
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 1);
    const auto reverse = edges.find({edge.second, edge.first});
    ASSERT_NE(reverse, edges.end());
    EXPECT_EQ(reverse->second, 1);
  }
}

// The body's volume less its cavities, from the drawing's sizes (the EPFL body: 70 x 22 x (2 + 8 + 7) mm less seven
// 2 x 8 x 8 mm cavities), to 1e-9.
TEST(BodyMesh, EnclosesTheBodyLessItsCavities) {
  const pf::ActuatorDrawing d = epflDrawing(0.002);
  const double body = 0.070 * 0.022 * 0.017, cavities = 7 * 0.002 * 0.008 * 0.008;
  EXPECT_NEAR(pf::meshVolume(pf::drawnBodyMesh(d)), body - cavities, 1e-9 * (body - cavities));
  EXPECT_NEAR(d.body_width_m, 0.022, 1e-15);  // the default: the cavity and a wall each side
}

// The STL's corners are the mesh's, read back exactly; its facets as many as the triangles.
TEST(BodyMesh, TheStlReadsBackToTheSameCorners) {
  const std::vector<pf::MeshTriangle> mesh = pf::drawnBodyMesh(epflDrawing(0.002));
  std::istringstream stl(pf::meshToStl(mesh, "body"));
  std::string word;
  std::vector<double> read;
  int facets = 0;
  while (stl >> word) {
    if (word == "facet") ++facets;
    if (word != "vertex") continue;
    for (int k = 0; k < 3 && stl >> word; ++k) read.push_back(std::strtod(word.c_str(), nullptr));
  }
  ASSERT_EQ(facets, static_cast<int>(mesh.size()));
  ASSERT_EQ(read.size(), 9 * mesh.size());
  for (std::size_t i = 0; i < mesh.size(); ++i) {
    const Eigen::Vector3d corners[3] = {mesh[i].a, mesh[i].b, mesh[i].c};
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 3; ++k) EXPECT_EQ(read[9 * i + 3 * c + k], corners[c][k]);
    }
  }
}

TEST(BodyMesh, RefusesADrawingItCannotClose) {
  try {
    pf::drawnBodyMesh(epflDrawing(0.0));
    ADD_FAILURE() << "a cavity on the bottom face was meshed";
  } catch (const pf::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("give drawing/layer_thickness_m"), std::string::npos) << e.what();
  }
  pf::ActuatorDrawing split = epflDrawing(0.002);
  split.gap_m = 0.001;
  EXPECT_THROW(pf::drawnBodyMesh(split), pf::ParameterError);
}
