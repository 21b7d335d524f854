#include <algorithm>
#include <numeric>

#include <gtest/gtest.h>

#include "deformcd/body.h"
#include "deformcd/error.h"
#include "support/mesh_fixtures.h"

namespace deformcd {
namespace {

TEST(BuildBody, PaperSpringsAreSixPerTetrahedron) {
  const Body body = build_body(test::unit_cube());
  EXPECT_EQ(body.positions.size(), 8u);
  EXPECT_EQ(body.tetrahedra.size(), 5u);
  EXPECT_EQ(body.springs.size(), 30u);
  EXPECT_EQ(body.faces.size(), 12u);
  EXPECT_EQ(body.face_normals.size(), 12u);
  for (const gpu::Spring& s : body.springs) {
    const float expected = glm::length(glm::vec3(body.positions[s.a] - body.positions[s.b]));
    EXPECT_FLOAT_EQ(s.rest_length, expected);
    EXPECT_NE(s.a, s.b);
  }
}

TEST(BuildBody, MergedSpringsAreTheDistinctEdges) {
  BodyOptions options;
  options.merge_shared_edges = true;
  const Body body = build_body(test::unit_cube(), options);
  // 12 cube edges + 6 face diagonals (the central tetrahedron's edges are all face diagonals).
  EXPECT_EQ(body.springs.size(), 18u);
  for (const gpu::Spring& s : body.springs)
    EXPECT_LT(s.a, s.b);
}

TEST(BuildBody, LumpedMassSumsToDensityTimesVolume) {
  BodyOptions options;
  options.density = 250.0;
  const Body body = build_body(test::unit_cube(), options);
  EXPECT_NEAR(body.volume, 1.0, 1e-12);
  const double total = std::accumulate(body.node_mass.begin(), body.node_mass.end(), 0.0);
  EXPECT_NEAR(total, 250.0, 1e-4);
  EXPECT_TRUE(
      std::all_of(body.node_mass.begin(), body.node_mass.end(), [](float m) { return m > 0; }));
}

// The unit cube's five tetrahedra give its corners two masses (a corner of the central
// tetrahedron carries a third of the cube's volume more): with the floor at the mean, every
// node's mass is at least the old mean, scaled back to the total; 0 keeps the pure lumping;
// outside [0, 1] is refused.
TEST(BuildBody, NodeMassesAreFlooredAtAShareOfTheMeanAndKeepTheTotal) {
  BodyOptions lumped;
  lumped.density = 250.0;
  lumped.node_mass_floor = 0.0;
  const Body plain = build_body(test::unit_cube(), lumped);
  const auto [light, heavy] = std::minmax_element(plain.node_mass.begin(), plain.node_mass.end());
  ASSERT_LT(*light * 1.5f, *heavy) << "the cube's masses should differ";
  BodyOptions floored = lumped;
  floored.node_mass_floor = 1.0;
  const Body body = build_body(test::unit_cube(), floored);
  const double total = std::accumulate(body.node_mass.begin(), body.node_mass.end(), 0.0);
  EXPECT_NEAR(total, 250.0, 1e-4);
  const auto [least, most] = std::minmax_element(body.node_mass.begin(), body.node_mass.end());
  EXPECT_GT(*least, *light) << "the light nodes should be raised";
  EXPECT_LT(*most, *heavy) << "and the others scaled down";
  EXPECT_LT(*most / *least, *heavy / *light);
  for (const double share : {-0.1, 1.5, std::nan("")}) {
    BodyOptions bad = lumped;
    bad.node_mass_floor = share;
    EXPECT_THROW((void)build_body(test::unit_cube(), bad), InputError) << share;
  }
}

TEST(BuildBody, NormalsAreUnitAndOutward) {
  const Body body = build_body(test::unit_cube());
  for (std::size_t i = 0; i < body.faces.size(); ++i) {
    const glm::vec3 n(body.face_normals[i]);
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
    const glm::vec3 p(body.positions[body.faces[i].a]);
    EXPECT_GT(glm::dot(n, p - glm::vec3(0.5f)), 0.0f);
  }
}

TEST(BuildBody, BoundsCoverTheNodes) {
  const Bounds b = compute_bounds(build_body(test::unit_cube()));
  EXPECT_EQ(b.min, glm::dvec3(0.0));
  EXPECT_EQ(b.max, glm::dvec3(1.0));
}

TEST(BuildBody, RejectsNodeWithoutTetrahedron) {
  TetMesh mesh = test::unit_tetrahedron();
  mesh.nodes.push_back({5, 5, 5});
  try {
    (void)build_body(mesh, {}, "lonely.node");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lonely.node: node 4"), std::string::npos) << e.what();
  }
}

TEST(BuildBody, RejectsNonPositiveDensity) {
  BodyOptions options;
  options.density = 0.0;
  EXPECT_THROW((void)build_body(test::unit_tetrahedron(), options), InputError);
}

}  // namespace
}  // namespace deformcd
