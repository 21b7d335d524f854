// OverlapFinder (deformcd/overlap.h) on cubes whose overlap is known by construction: the
// direction that shrinks the shared volume, the vertices inside and the face each leaves
// through, either winding, one cube wholly inside the other, and bad input.

#include "deformcd/overlap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "deformcd/error.h"
#include "support/mesh_fixtures.h"

namespace deformcd {
namespace {

CollisionMesh cube_mesh(bool inward = false) {
  CollisionMesh m{.vertex_count = 8, .triangles = test::cube_triangles()};
  if (inward)
    for (Triangle& t : m.triangles)
      std::swap(t[1], t[2]);
  return m;
}

std::vector<std::uint32_t> vertices_of(const std::vector<PenetratingVertex>& list) {
  std::vector<std::uint32_t> v;
  v.reserve(list.size());
  for (const PenetratingVertex& p : list)
    v.push_back(p.vertex);
  return v;
}

TEST(OverlapFinder, ApartCubesDoNotOverlap) {
  const OverlapFinder finder({cube_mesh(), cube_mesh()});
  EXPECT_TRUE(finder.closed(0));
  const Overlap o = finder.find(0, 1, test::cube_corners(glm::vec3(0.0f), 1.0f),
                                test::cube_corners(glm::vec3(1.5f), 1.0f));
  EXPECT_FALSE(o.any());
  EXPECT_EQ(o.direction, glm::vec3(0.0f));
}

// A 0.6 cube entering the unit cube through its x = 1 side, 0.3 deep: its four corners at
// x = 0.7 are inside, each leaves 0.3 further along +x through the unit cube's x = 1 side; the
// unit cube has no corner inside the small one. The direction is +x with either winding.
TEST(OverlapFinder, ACubeEnteringAnotherLeavesTheWayItCameThroughTheFaceItEntered) {
  for (const bool inward : {false, true}) {
    SCOPED_TRACE(inward ? "inward winding" : "outward winding");
    const OverlapFinder finder({cube_mesh(inward), cube_mesh(!inward)});
    const Overlap o = finder.find(0, 1, test::cube_corners(glm::vec3(0.7f, 0.2f, 0.2f), 0.6f),
                                  test::cube_corners(glm::vec3(0.0f), 1.0f));
    EXPECT_NEAR(o.direction.x, 1.0f, 1e-6f);
    EXPECT_NEAR(o.direction.y, 0.0f, 1e-6f);
    EXPECT_NEAR(o.direction.z, 0.0f, 1e-6f);
    EXPECT_EQ(vertices_of(o.a_in_b), (std::vector<std::uint32_t>{0, 3, 4, 7}));
    for (const PenetratingVertex& p : o.a_in_b) {
      EXPECT_TRUE(p.triangle == 6u || p.triangle == 7u) << "vertex " << p.vertex;
      EXPECT_NEAR(p.depth, 0.3f, 1e-6f);
    }
    EXPECT_TRUE(o.b_in_a.empty());
    // The same pair the other way round: the direction reversed, the lists swapped.
    const Overlap swapped = finder.find(1, 0, test::cube_corners(glm::vec3(0.0f), 1.0f),
                                        test::cube_corners(glm::vec3(0.7f, 0.2f, 0.2f), 0.6f));
    EXPECT_NEAR(swapped.direction.x, -1.0f, 1e-6f);
    EXPECT_TRUE(swapped.a_in_b.empty());
    EXPECT_EQ(vertices_of(swapped.b_in_a), vertices_of(o.a_in_b));
  }
}

// Two unit cubes crossed by (0.5, 0.1, 0.1): one corner of each is inside the other. The
// shared box is 0.5 x 0.9 x 0.9, so moving the first cube along (0.81, 0.45, 0.45) shrinks it
// fastest; two triangles a side give a coarse estimate of that, still away along every axis.
// Each corner leaves along the direction (or against it) through the other's far side.
TEST(OverlapFinder, CrossedCubesLeaveEachOtherOppositeWays) {
  const OverlapFinder finder({cube_mesh(), cube_mesh()});
  const Overlap o = finder.find(0, 1, test::cube_corners(glm::vec3(0.5f, 0.1f, 0.1f), 1.0f),
                                test::cube_corners(glm::vec3(0.0f), 1.0f));
  EXPECT_GT(o.direction.x, 0.5f);
  EXPECT_GT(o.direction.y, 0.1f);
  EXPECT_GT(o.direction.z, 0.1f);
  ASSERT_EQ(o.a_in_b.size(), 1u);  // (0.5, 0.1, 0.1): leaves through x = 1 first
  EXPECT_EQ(o.a_in_b[0].vertex, 0u);
  EXPECT_TRUE(o.a_in_b[0].triangle == 6u || o.a_in_b[0].triangle == 7u);
  EXPECT_NEAR(o.a_in_b[0].depth, 0.5f / o.direction.x, 1e-5f);
  ASSERT_EQ(o.b_in_a.size(), 1u);  // (1, 1, 1): leaves the first cube through its x = 0 side
  EXPECT_EQ(o.b_in_a[0].vertex, 6u);
  EXPECT_TRUE(o.b_in_a[0].triangle == 10u || o.b_in_a[0].triangle == 11u);
  EXPECT_NEAR(o.b_in_a[0].depth, 0.5f / o.direction.x, 1e-5f);
}

// A small cube wholly inside a big one: the fluxes cancel (no surface of the big one is inside
// the small one, all of the small one's is inside the big one), so the direction is from the
// big one's centre to the small one's; every corner of the small one leaves along it.
TEST(OverlapFinder, ACubeWhollyInsideLeavesFromTheCentreOutward) {
  const OverlapFinder finder({cube_mesh(), cube_mesh()});
  const Overlap o = finder.find(0, 1, test::cube_corners(glm::vec3(0.5f, 0.3f, 0.3f), 0.4f),
                                test::cube_corners(glm::vec3(0.0f), 1.0f));
  EXPECT_NEAR(o.direction.x, 1.0f, 1e-6f);
  EXPECT_EQ(o.a_in_b.size(), 8u);
  for (const PenetratingVertex& p : o.a_in_b) {
    const float x =
        p.vertex == 0u || p.vertex == 3u || p.vertex == 4u || p.vertex == 7u ? 0.5f : 0.9f;
    EXPECT_NEAR(p.depth, 1.0f - x, 1e-6f) << "vertex " << p.vertex;
  }
  EXPECT_TRUE(o.b_in_a.empty());
}

TEST(OverlapFinder, AnOpenMeshHasNoInside) {
  CollisionMesh open = cube_mesh();
  open.triangles.pop_back();
  const OverlapFinder finder({cube_mesh(), open});
  EXPECT_FALSE(finder.closed(1));
  EXPECT_FALSE(finder
                   .find(0, 1, test::cube_corners(glm::vec3(0.7f, 0.2f, 0.2f), 0.6f),
                         test::cube_corners(glm::vec3(0.0f), 1.0f))
                   .any());
}

TEST(OverlapFinder, BadInputIsAnErrorNamingWhatIsWrong) {
  CollisionMesh named = cube_mesh();
  named.name = "lid";
  const OverlapFinder finder({cube_mesh(), named});
  const std::vector<glm::vec3> unit = test::cube_corners(glm::vec3(0.0f), 1.0f);
  EXPECT_THROW((void)finder.find(0, 0, unit, unit), InputError);
  EXPECT_THROW((void)finder.find(0, 2, unit, unit), InputError);
  std::vector<glm::vec3> nan = unit;
  nan[5].y = std::numeric_limits<float>::quiet_NaN();
  try {
    (void)finder.find(0, 1, unit, nan);
    FAIL() << "a NaN position was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mesh 1 ('lid') vertex 5"), std::string::npos) << e.what();
  }
  const std::vector<glm::vec3> short_list(unit.begin(), unit.end() - 1);
  EXPECT_THROW((void)finder.find(0, 1, short_list, unit), InputError);
  CollisionMesh broken = cube_mesh();
  broken.triangles[3][1] = 8;
  EXPECT_THROW(OverlapFinder({broken}), InputError);
}

}  // namespace
}  // namespace deformcd
