#include <gtest/gtest.h>

#include "deformcd/error.h"
#include "deformcd/scene.h"
#include "support/mesh_fixtures.h"

namespace deformcd {
namespace {

Scene one_cube(const BodySpec& spec) {
  Scene s;
  s.file = "test.json";
  s.settings.dt = 0.01;
  s.bodies = {spec};
  return s;
}

TetMesh load_cube(const std::filesystem::path&) {
  return test::unit_cube();
}

TEST(SceneBodies, PlacesScalesAndRotates) {
  BodySpec spec;
  spec.name = "c";
  spec.position = {10, 0, 0};
  spec.scale = glm::dvec3(2.0);
  spec.rotation = {0, 0, 90};  // x -> y
  const auto bodies = make_scene_bodies(one_cube(spec), load_cube, 100);
  ASSERT_EQ(bodies.size(), 1u);
  // Node 1 of the cube is (1, 0, 0): scaled to (2, 0, 0), rotated to (0, 2, 0), moved.
  const glm::vec4 p = bodies[0].body.positions[1];
  EXPECT_NEAR(p.x, 10.0f, 1e-5f);
  EXPECT_NEAR(p.y, 2.0f, 1e-5f);
  EXPECT_NEAR(p.z, 0.0f, 1e-5f);
}

// A body whose material sets no node mass floor gets kResponseNodeMassFloor in a scene with a
// response and pure lumping without one; a floor the material sets (0 included) is kept.
TEST(SceneBodies, AResponseFloorsTheNodeMassesUnlessTheMaterialSaysOtherwise) {
  // Two tetrahedra on one face, the second a hundredth as high: its apex is the lightest node.
  const auto load_wedge = [](const std::filesystem::path&) {
    TetMesh m;
    m.nodes = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -0.01}};
    m.tetrahedra = {{0, 1, 2, 3}, {0, 2, 1, 4}};
    return m;
  };
  const auto masses = [&](std::optional<double> floor, bool response) {
    BodySpec spec;
    spec.material.node_mass_floor = floor;
    Scene scene = one_cube(spec);
    if (response) scene.response = ResponseSettings{};
    return make_scene_bodies(scene, load_wedge, 100)[0].body.node_mass;
  };
  const std::vector<float> lumped = masses(0.0, false);
  const std::vector<float> floored = masses(kResponseNodeMassFloor, false);
  ASSERT_NE(lumped, floored) << "the thin tetrahedron's apex should be floored";
  EXPECT_EQ(masses(std::nullopt, false), lumped);
  EXPECT_EQ(masses(std::nullopt, true), floored);
  EXPECT_EQ(masses(0.0, true), lumped);
  EXPECT_EQ(masses(0.5, true), masses(0.5, false));
}

TEST(SceneBodies, SquashDeformsThePoseButNotTheRestLengths) {
  BodySpec spec;
  spec.squash = {1.0, 0.5, 1.0};
  const auto plain = make_scene_bodies(one_cube(BodySpec{}), load_cube, 100);
  const auto squashed = make_scene_bodies(one_cube(spec), load_cube, 100);
  const Body& a = plain[0].body;
  const Body& b = squashed[0].body;
  ASSERT_EQ(a.springs.size(), b.springs.size());
  for (std::size_t s = 0; s < a.springs.size(); ++s) {
    EXPECT_EQ(a.springs[s].rest_length, b.springs[s].rest_length);
  }
  // The cube's height halves about the centroid (y = 0.5).
  EXPECT_NEAR(b.positions[3].y, 0.75f, 1e-6f);  // node 3 is (0, 1, 0)
  EXPECT_NEAR(b.positions[0].y, 0.25f, 1e-6f);
}

TEST(SceneBodies, PathSpansTheFrames) {
  BodySpec spec;
  spec.position = {0, 0, 0};
  spec.path_to = glm::dvec3(3, 0, 0);
  const auto bodies = make_scene_bodies(one_cube(spec), load_cube, 150);  // 150 x 0.01 s
  EXPECT_NEAR(bodies[0].carry_velocity.x, 2.0f, 1e-5f);
}

TEST(SceneBodies, MassAndFixedBox) {
  BodySpec spec;
  spec.material.mass = 8.0;
  Bounds box;
  box.min = {-1, 0.9, -1};
  box.max = {2, 2, 2};
  spec.fixed.box = box;
  const auto bodies = make_scene_bodies(one_cube(spec), load_cube, 10);
  for (float m : bodies[0].body.node_mass)
    EXPECT_FLOAT_EQ(m, 1.0f);                                            // 8 kg over 8 nodes
  EXPECT_EQ(bodies[0].fixed, (std::vector<std::uint32_t>{2, 3, 6, 7}));  // the y = 1 nodes

  box.min = {5, 5, 5};
  box.max = {6, 6, 6};
  spec.fixed.box = box;
  EXPECT_THROW((void)make_scene_bodies(one_cube(spec), load_cube, 10), InputError);
}

TEST(SceneBodies, AMeshingLoaderGetsEachBodysMeshingAndLoadsEachDistinctOneOnce) {
  BodySpec coarse;
  coarse.model = "cube.off";
  BodySpec fine = coarse;
  fine.meshing.max_volume = 0.1;
  Scene scene = one_cube(coarse);
  scene.bodies = {coarse, fine, coarse};
  std::vector<TetrahedralizeOptions> seen;
  const auto bodies = make_scene_bodies(
      scene,
      [&seen](const std::filesystem::path&, const TetrahedralizeOptions& meshing) {
        seen.push_back(meshing);
        return test::unit_cube();
      },
      10);
  EXPECT_EQ(bodies.size(), 3u);
  ASSERT_EQ(seen.size(), 2u);  // the third body shares the first one's mesh
  EXPECT_EQ(seen[0].quality, 2.0);
  EXPECT_TRUE(seen[0].preserve_surface);
  EXPECT_FALSE(seen[0].max_volume.has_value());
  EXPECT_EQ(seen[1].max_volume, 0.1);
}

}  // namespace
}  // namespace deformcd
