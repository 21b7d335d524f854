#include "deformcd/tetrahedralize.h"

#include <algorithm>
#include <set>

#include <gtest/gtest.h>

#include "deformcd/body.h"
#include "deformcd/error.h"
#include "support/mesh_fixtures.h"

namespace deformcd {
namespace {

std::set<Triangle> sorted_triangles(const std::vector<Triangle>& tris) {
  std::set<Triangle> out;
  for (Triangle t : tris) {
    std::sort(t.begin(), t.end());
    out.insert(t);
  }
  return out;
}

std::string error_of(const SurfaceMesh& s, const TetrahedralizeOptions& o = {}) {
  try {
    (void)tetrahedralize(s, o, "input.off");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Tetrahedralize, OctahedronFillsItsVolume) {
  const TetMesh mesh = tetrahedralize(test::octahedron());
  const Body body = build_body(mesh);
  EXPECT_NEAR(body.volume, 4.0 / 3.0, 1e-9);  // two square pyramids of height 1, base 2
  EXPECT_GE(mesh.tetrahedra.size(), 4u);
}

TEST(Tetrahedralize, PreserveSurfaceKeepsVerticesInOrderAndTrianglesExactly) {
  const SurfaceMesh surface = test::sphere(3);  // 258 vertices, 512 triangles
  TetrahedralizeOptions options;
  options.preserve_surface = true;
  options.quality = 1.2;
  options.max_volume = 0.005;  // forces interior nodes
  const TetMesh mesh = tetrahedralize(surface, options);
  ASSERT_GT(mesh.nodes.size(), surface.vertices.size());
  for (std::size_t i = 0; i < surface.vertices.size(); ++i) {
    EXPECT_EQ(mesh.nodes[i], surface.vertices[i]) << "node " << i;
  }
  const Body body = build_body(mesh);
  std::vector<Triangle> boundary;
  for (const gpu::Face& f : body.faces)
    boundary.push_back({f.a, f.b, f.c});
  EXPECT_EQ(sorted_triangles(boundary), sorted_triangles(surface.triangles));
}

TEST(Tetrahedralize, MaxVolumeRefines) {
  TetrahedralizeOptions coarse, fine;
  fine.max_volume = 0.001;
  EXPECT_GT(tetrahedralize(test::octahedron(), fine).tetrahedra.size(),
            10 * tetrahedralize(test::octahedron(), coarse).tetrahedra.size());
}

TEST(Tetrahedralize, RejectsOpenSurfaceNamingTheEdge) {
  SurfaceMesh open = test::octahedron();
  open.triangles.pop_back();
  const std::string msg = error_of(open);
  EXPECT_NE(msg.find("input.off"), std::string::npos) << msg;
  EXPECT_NE(msg.find("3 boundary edge(s)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("hole"), std::string::npos) << msg;
}

TEST(Tetrahedralize, RejectsInconsistentOrientation) {
  SurfaceMesh flipped = test::octahedron();
  std::swap(flipped.triangles[0][0], flipped.triangles[0][1]);
  EXPECT_NE(error_of(flipped).find("inconsistent orientation"), std::string::npos);
}

TEST(Tetrahedralize, ReportsSelfIntersectionWithoutAborting) {
  // Two octahedra, the second shifted into the first: closed and oriented, but intersecting.
  SurfaceMesh both = test::octahedron();
  const SurfaceMesh second = test::octahedron();
  for (const auto& v : second.vertices)
    both.vertices.push_back(v + glm::dvec3(0.5, 0.3, 0.2));
  for (const auto& t : second.triangles)
    both.triangles.push_back({t[0] + 6, t[1] + 6, t[2] + 6});
  const std::string msg = error_of(both);
  EXPECT_NE(msg.find("input.off"), std::string::npos) << msg;
  EXPECT_NE(msg.find("intersects itself"), std::string::npos) << msg;
}

TEST(Tetrahedralize, RejectsBadOptions) {
  TetrahedralizeOptions o;
  o.quality = 0.5;
  EXPECT_NE(error_of(test::octahedron(), o).find("quality"), std::string::npos);
  o = {};
  o.max_volume = -1.0;
  EXPECT_NE(error_of(test::octahedron(), o).find("max volume"), std::string::npos);
}

}  // namespace
}  // namespace deformcd
