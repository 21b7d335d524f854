#include "core/surface_extraction.h"

#include <algorithm>
#include <map>

#include <gtest/gtest.h>

#include "deformcd/error.h"
#include "support/mesh_fixtures.h"

namespace deformcd {
namespace {

glm::dvec3 normal_of(const TetMesh& m, const Triangle& t) {
  return glm::cross(m.nodes[t[1]] - m.nodes[t[0]], m.nodes[t[2]] - m.nodes[t[0]]);
}

TEST(ExtractBoundary, SingleTetrahedronHasFourOutwardFaces) {
  const TetMesh tet = test::unit_tetrahedron();
  const auto faces = extract_boundary(tet.tetrahedra, "tet");
  ASSERT_EQ(faces.size(), 4u);
  const glm::dvec3 centroid = (tet.nodes[0] + tet.nodes[1] + tet.nodes[2] + tet.nodes[3]) / 4.0;
  for (const Triangle& f : faces) {
    EXPECT_GT(glm::dot(normal_of(tet, f), tet.nodes[f[0]] - centroid), 0.0);
  }
}

TEST(ExtractBoundary, CubeSurfaceIsClosedOutwardAndSkipsInteriorFaces) {
  const TetMesh cube = test::unit_cube();
  const auto faces = extract_boundary(cube.tetrahedra, "cube");
  ASSERT_EQ(faces.size(), 12u);  // 2 per cube side; the 4 inner faces are shared
  const glm::dvec3 centre(0.5);
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  double signed_volume = 0.0;  // divergence theorem: sum over faces of dot(p0, n)/6
  for (const Triangle& f : faces) {
    EXPECT_GT(glm::dot(normal_of(cube, f), cube.nodes[f[0]] - centre), 0.0);
    for (int k = 0; k < 3; ++k)
      directed[{f[k], f[(k + 1) % 3]}]++;
    signed_volume += glm::dot(cube.nodes[f[0]], normal_of(cube, f)) / 6.0;
  }
  // Closed and consistently oriented: each directed edge once, and its reverse once.
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
  }
  EXPECT_NEAR(signed_volume, 1.0, 1e-12);
}

TEST(ExtractBoundary, RejectsFaceSharedByThreeTetrahedra) {
  TetMesh tet = test::unit_tetrahedron();
  tet.nodes.push_back({0.2, 0.2, -1.0});
  tet.nodes.push_back({0.3, 0.3, 2.0});
  // Face (0,1,2) used by the original tetrahedron, one below it and a third overlapping one.
  tet.tetrahedra.push_back({0, 2, 1, 4});
  tet.tetrahedra.push_back({0, 1, 2, 5});
  try {
    (void)extract_boundary(tet.tetrahedra, "three.ele");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("three.ele"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("more than two tetrahedra"), std::string::npos)
        << e.what();
  }
}

TEST(ExtractBoundary, RejectsOverlappingTetrahedraOnOneSide) {
  TetMesh tet = test::unit_tetrahedron();
  tet.nodes.push_back({0.3, 0.3, 2.0});
  tet.tetrahedra.push_back({0, 1, 2, 4});  // same side of face (0,1,2) as node 3
  EXPECT_THROW((void)extract_boundary(tet.tetrahedra, "overlap"), InputError);
}

}  // namespace
}  // namespace deformcd
