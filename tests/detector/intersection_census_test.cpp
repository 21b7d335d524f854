// The intersection census (deformcd/intersection_census.h) on cases whose answer is known by
// construction: apart, crossing, nested (a body wholly inside another: no triangle pair, every
// vertex inside), a surface folded through itself, a vertex on the other surface, an open mesh.

#include "deformcd/intersection_census.h"

#include <gtest/gtest.h>

#include <limits>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "deformcd/error.h"
#include "detector/closed_surface_inside.h"
#include "support/mesh_fixtures.h"

namespace deformcd {
namespace {

CollisionMesh cube_mesh() {
  return {.vertex_count = 8, .triangles = test::cube_triangles()};
}

IntersectionCensus census_of(const std::vector<CollisionMesh>& meshes,
                             const std::vector<std::vector<glm::vec3>>& positions) {
  IntersectionCounter counter(meshes);
  std::vector<std::span<const glm::vec3>> views(positions.begin(), positions.end());
  return counter.count(views);
}

TEST(IntersectionCensus, CubeIsClosedAndAnOpenSheetIsNot) {
  EXPECT_TRUE(collision::surface_closed(test::cube_triangles()));
  std::vector<Triangle> open(test::cube_triangles().begin(), test::cube_triangles().end() - 1);
  EXPECT_FALSE(collision::surface_closed(open));
}

TEST(IntersectionCensus, ApartCubesCountNothing) {
  const IntersectionCensus c = census_of(
      {cube_mesh(), cube_mesh()},
      {test::cube_corners(glm::vec3(0.0f), 1.0f), test::cube_corners(glm::vec3(1.5f), 1.0f)});
  EXPECT_EQ(c.between_pairs, 0u);
  EXPECT_EQ(c.self_pairs, 0u);
  EXPECT_EQ(c.inside_vertices, 0u);
  EXPECT_FALSE(c.any());
}

TEST(IntersectionCensus, OverlappingCubesCountPairsAndTheOneCornerInside) {
  // The second cube's corner (0.5, 0.5, 0.5) is inside the first and the first's corner
  // (1, 1, 1) inside the second; their faces cross.
  const IntersectionCensus c = census_of(
      {cube_mesh(), cube_mesh()},
      {test::cube_corners(glm::vec3(0.0f), 1.0f), test::cube_corners(glm::vec3(0.5f), 1.0f)});
  EXPECT_GT(c.between_pairs, 0u);
  EXPECT_EQ(c.self_pairs, 0u);
  EXPECT_EQ(c.inside_vertices, 2u);
}

TEST(IntersectionCensus, NestedCubeHasNoPairButEveryVertexInside) {
  // What a count of intersecting pairs alone cannot see: a body wholly through another.
  const IntersectionCensus c = census_of(
      {cube_mesh(), cube_mesh()},
      {test::cube_corners(glm::vec3(0.0f), 1.0f), test::cube_corners(glm::vec3(0.25f), 0.5f)});
  EXPECT_EQ(c.between_pairs, 0u);
  EXPECT_EQ(c.self_pairs, 0u);
  EXPECT_EQ(c.inside_vertices, 8u);
}

TEST(IntersectionCensus, SurfaceFoldedThroughItselfCountsSelfPairs) {
  // One mesh made of two overlapping cubes: its surface crosses itself, and no other mesh is
  // there to count a pair with.
  std::vector<Triangle> triangles = test::cube_triangles();
  for (const Triangle& t : test::cube_triangles())
    triangles.push_back({t[0] + 8u, t[1] + 8u, t[2] + 8u});
  std::vector<glm::vec3> positions = test::cube_corners(glm::vec3(0.0f), 1.0f);
  const std::vector<glm::vec3> second = test::cube_corners(glm::vec3(0.5f), 1.0f);
  positions.insert(positions.end(), second.begin(), second.end());
  const IntersectionCensus c =
      census_of({{.vertex_count = 16, .triangles = triangles}}, {positions});
  EXPECT_EQ(c.between_pairs, 0u);
  EXPECT_GT(c.self_pairs, 0u);
  EXPECT_EQ(c.inside_vertices, 0u);  // one mesh: nothing else to be inside
}

TEST(IntersectionCensus, NeighbouringTrianglesOfOneSurfaceAreNotPairs) {
  const IntersectionCensus c =
      census_of({cube_mesh()}, {test::cube_corners(glm::vec3(0.0f), 1.0f)});
  EXPECT_EQ(c.self_pairs, 0u);
}

TEST(IntersectionCensus, VertexOnTheOtherSurfaceIsNotInsideAndJustBelowItIs) {
  // A small cube whose corner (0.5, 0.5, 1) lies on the big cube's top face, where the ray
  // along x passes through the face's diagonal edge: the rays are uncertain there, which the
  // parity must not get wrong.
  std::vector<glm::vec3> small = test::cube_corners(glm::vec3(0.5f, 0.5f, 1.0f), 0.25f);
  IntersectionCounter counter({cube_mesh(), cube_mesh()});
  const std::vector<glm::vec3> big = test::cube_corners(glm::vec3(0.0f), 1.0f);
  std::vector<std::span<const glm::vec3>> views = {big, small};
  EXPECT_EQ(counter.count(views).inside_vertices, 0u);
  for (glm::vec3& p : small)
    p.z -= 1e-6f;  // the lower four corners now just inside (and the faces cross)
  EXPECT_EQ(counter.count(views).inside_vertices, 4u);
}

TEST(IntersectionCensus, OpenMeshHasNoInside) {
  std::vector<Triangle> open(test::cube_triangles().begin() + 2,
                             test::cube_triangles().end());  // no bottom
  IntersectionCounter counter({{.vertex_count = 8, .triangles = open}, cube_mesh()});
  EXPECT_FALSE(counter.closed(0));
  EXPECT_TRUE(counter.closed(1));
  const std::vector<glm::vec3> big = test::cube_corners(glm::vec3(0.0f), 1.0f);
  const std::vector<glm::vec3> small = test::cube_corners(glm::vec3(0.25f), 0.5f);
  std::vector<std::span<const glm::vec3>> views = {big, small};
  EXPECT_EQ(counter.count(views).inside_vertices, 0u);
}

TEST(IntersectionCensus, WrongPositionCountsAndNonFinitePositionsAreErrors) {
  IntersectionCounter counter({cube_mesh()});
  std::vector<glm::vec3> short_list(7, glm::vec3(0.0f));
  std::vector<std::span<const glm::vec3>> views = {short_list};
  EXPECT_THROW((void)counter.count(views), InputError);
  std::vector<glm::vec3> bad = test::cube_corners(glm::vec3(0.0f), 1.0f);
  bad[3].x = std::numeric_limits<float>::quiet_NaN();
  views = {bad};
  EXPECT_THROW((void)counter.count(views), InputError);
}

}  // namespace
}  // namespace deformcd
