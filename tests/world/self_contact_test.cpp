// SelfContact (issue 33): a body's self-contact pairs kept from one search while it moves as a
// whole. The kept pairs must hold every pair of its surface within the thickness wherever a
// rigid motion, plus a drift below the margin, takes it; a body that deforms past the margin,
// or fast, must give its pairs up; and a world whose bodies fly at a constant velocity searches
// each body against itself once.

#include <array>
#include <cmath>
#include <filesystem>
#include <set>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "deformcd/detector.h"
#include "deformcd/error.h"
#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "deformcd/world.h"
#include "support/collision_fixtures.h"
#include "world/contact_response.h"
#include "world/self_contact.h"

namespace fs = std::filesystem;

namespace deformcd {
namespace {

// The impact scene's lion alone (5,156 surface triangles), its thickness the response's default
// (0.2 of its mean surface edge).
struct Lion {
  std::vector<BodyInit> bodies;
  SimulationState state;
  std::vector<std::uint8_t> on_surface;
  float thickness = 0.0f;
  std::vector<glm::vec3> rest;
};

Lion lion() {
  const Scene scene = read_scene(fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / "impact.json");
  Lion out;
  out.bodies.push_back(make_scene_bodies(scene, read_tetgen, 1).at(1));
  out.state = assemble_simulation(out.bodies);
  out.on_surface.assign(out.state.positions.size(), 0u);
  for (const gpu::Face& f : out.bodies[0].body.faces)
    out.on_surface[f.a] = out.on_surface[f.b] = out.on_surface[f.c] = 1u;
  out.thickness = 0.2f * mean_surface_edge(out.bodies[0].body);
  for (const glm::vec4& x : out.state.positions)
    out.rest.emplace_back(x);
  return out;
}

// A pair as its kind and its nodes (what the response makes a constraint of).
using PairKey = std::array<std::uint32_t, 5>;
std::set<PairKey> keys(const std::vector<ProximityPair>& pairs) {
  std::set<PairKey> out;
  for (const ProximityPair& p : pairs)
    out.insert({static_cast<std::uint32_t>(p.kind), p.vertices[0], p.vertices[1], p.vertices[2],
                p.vertices[3]});
  return out;
}

std::vector<glm::vec4> with_w(const std::vector<glm::vec3>& x) {
  std::vector<glm::vec4> out;
  for (const glm::vec3& p : x)
    out.emplace_back(p, 1.0f);
  return out;
}

// A fixed direction per node, of length 1 (a drift that is not a rigid motion).
glm::vec3 direction(std::size_t i) {
  const auto f = static_cast<float>(i);
  return glm::normalize(glm::vec3(std::sin(1.7f * f + 0.3f), std::cos(2.3f * f + 1.1f),
                                  std::sin(0.7f * f + 2.9f) + 0.01f));
}

class SelfContactTest : public ::testing::Test {
 protected:
  void SetUp() override {
    l_ = lion();
    detector_ = std::make_unique<Detector>(test::surface_meshes(l_.bodies, true),
                                           DetectorOptions{.backend = BackendKind::kCpu});
    pose_ = l_.rest;
    detector_->set_positions(0, std::span<const glm::vec3>(pose_));
    self_ = std::make_unique<SelfContact>(l_.state.objects, l_.on_surface,
                                          std::vector<float>{l_.thickness});
    const std::vector<std::uint8_t> all{1u};
    self_->take(detector_->find_proximity(self_->search_reach(), {}, {}, {.between = false}),
                l_.rest, all);
    margin_ = SelfContact::kMargin * l_.thickness;
  }

  // The pairs of the surface at positions y within the thickness (a search with half the
  // thickness as reach, no motion, keeps a superset; the distance picks them).
  std::set<PairKey> within_thickness(const std::vector<glm::vec3>& y) {
    pose_ = y;
    std::vector<ProximityPair> close;
    for (const ProximityPair& p :
         detector_->find_proximity(std::vector<float>{0.5f * l_.thickness}, {}, {}))
      if (p.distance <= l_.thickness) close.push_back(p);
    return keys(close);
  }

  Lion l_;
  std::vector<glm::vec3> pose_;  // the detector reads it
  std::unique_ptr<Detector> detector_;
  std::unique_ptr<SelfContact> self_;
  float margin_ = 0.0f;
};

TEST_F(SelfContactTest, KeptPairsHoldEveryCloseOneAfterARigidMotionAndADriftBelowTheMargin) {
  // Turned by 35 degrees, moved by a metre, and each vertex drifted by 0.45 of the margin in a
  // direction of its own: closer pairs appear (the drift closes gaps), and all are kept.
  const glm::quat turn = glm::angleAxis(glm::radians(35.0f), glm::normalize(glm::vec3(1, 2, 3)));
  std::vector<glm::vec3> y(l_.rest.size());
  for (std::size_t i = 0; i < y.size(); ++i)
    y[i] = turn * l_.rest[i] + glm::vec3(0.3f, -0.2f, 1.0f) + 0.45f * margin_ * direction(i);
  const std::vector<glm::vec4> still(y.size(), glm::vec4(0.0f));
  EXPECT_TRUE(self_->holds(0, with_w(y), still, 1e-3f));
  const std::set<PairKey> kept = keys(self_->pairs(0));
  const std::set<PairKey> close = within_thickness(y);
  EXPECT_GT(close.size(), 100u);
  std::size_t missing = 0;
  for (const PairKey& k : close)
    missing += kept.count(k) == 0u ? 1u : 0u;
  EXPECT_EQ(missing, 0u) << "of " << close.size() << " pairs within the thickness";

  // One vertex drifted by 1.5 margins more: the pairs no longer hold.
  std::size_t moved = 0;
  while (l_.on_surface[moved] == 0u)
    ++moved;
  y[moved] += 1.5f * margin_ * direction(moved);
  EXPECT_FALSE(self_->holds(0, with_w(y), still, 1e-3f));
}

TEST_F(SelfContactTest, PlanKeepsABodyMovingAsAWholeAndLeavesOneThatDeformsFast) {
  glm::vec3 centre(0.0f);
  for (const glm::vec3& x : l_.rest)
    centre += x / static_cast<float>(l_.rest.size());
  const float window = 1e-2f;
  const std::vector<std::uint8_t> movable{1u};
  // Thrown and spinning at 5 rad/s: a rigid motion, kept.
  std::vector<glm::vec4> spin(l_.rest.size());
  for (std::size_t i = 0; i < spin.size(); ++i)
    spin[i] =
        glm::vec4(glm::vec3(2, 0, -1) + glm::cross(glm::vec3(0, 5, 0), l_.rest[i] - centre), 0.0f);
  EXPECT_EQ(self_->plan(l_.rest, spin, window, movable).kept[0], 1u);
  // Swelling at 5 m/s per metre from its centre: its pairs are the window search's.
  std::vector<glm::vec4> swell(l_.rest.size());
  for (std::size_t i = 0; i < swell.size(); ++i)
    swell[i] = glm::vec4(5.0f * (l_.rest[i] - centre), 0.0f);
  const SelfContact::Plan fast = self_->plan(l_.rest, swell, window, movable);
  EXPECT_EQ(fast.kept[0], 0u);
  EXPECT_EQ(fast.search[0], 0u);
  // Still, but drifted past the margin since its search: searched again.
  std::vector<glm::vec3> drifted = l_.rest;
  for (std::size_t i = 0; i < drifted.size(); ++i)
    drifted[i] += 1.5f * margin_ * direction(i);
  const std::vector<glm::vec4> still(l_.rest.size(), glm::vec4(0.0f));
  const SelfContact::Plan again = self_->plan(drifted, still, window, movable);
  EXPECT_EQ(again.kept[0], 0u);
  EXPECT_EQ(again.search[0], 1u);
  // A body that cannot move is left alone.
  EXPECT_EQ(self_->plan(l_.rest, still, window, {0u}).kept[0], 0u);
}

// find_proximity's mesh-pair filter: the pairs between meshes alone, each mesh's with itself
// alone, or some meshes' with themselves left out, are exactly those pairs of the whole search,
// in its order.
TEST(ProximityPairsFilter, SplitsTheWholeSearchExactly) {
  Lion a = lion();
  std::vector<BodyInit> bodies{a.bodies[0], a.bodies[0]};
  for (glm::vec4& x : bodies[1].body.positions)
    x += glm::vec4(0.05f, 0.02f, 0.0f, 0.0f);  // a few centimetres over: the surfaces cross
  Detector detector(test::surface_meshes(bodies, true), {.backend = BackendKind::kCpu});
  std::array<std::vector<glm::vec3>, 2> x;
  for (std::size_t b = 0; b < 2; ++b) {
    for (const glm::vec4& p : bodies[b].body.positions)
      x[b].emplace_back(p);
    detector.set_positions(b, std::span<const glm::vec3>(x[b]));
  }
  const std::vector<float> reach{0.5f * a.thickness, 0.5f * a.thickness};
  const std::vector<ProximityPair> all = detector.find_proximity(reach);
  const std::vector<ProximityPair> between = detector.find_proximity(reach, {}, {}, {.within = {}});
  const std::vector<std::uint8_t> none{0u, 0u}, second{0u, 1u};
  const std::vector<ProximityPair> only_between =
      detector.find_proximity(reach, {}, {}, {.within = none});
  const std::vector<ProximityPair> within =
      detector.find_proximity(reach, {}, {}, {.between = false});
  const std::vector<ProximityPair> second_within =
      detector.find_proximity(reach, {}, {}, {.between = false, .within = second});
  EXPECT_EQ(between, all);
  std::vector<ProximityPair> expect_between, expect_within, expect_second;
  for (const ProximityPair& p : all) {
    (p.mesh_a == p.mesh_b ? expect_within : expect_between).push_back(p);
    if (p.mesh_a == 1u && p.mesh_b == 1u) expect_second.push_back(p);
  }
  EXPECT_GT(expect_between.size(), 100u);
  EXPECT_GT(expect_second.size(), 100u);
  EXPECT_EQ(only_between, expect_between);
  EXPECT_EQ(within, expect_within);
  EXPECT_EQ(second_within, expect_second);
  EXPECT_THROW((void)detector.find_proximity(reach, {}, {}, {.within = std::span(second).first(1)}),
               InputError);
}

// The impact with self-contact (a response's default: WorldOptions::self_collision unset),
// before its bodies meet (frame 15): each body flies as a whole, so each is searched against
// itself once, in the first frame, and its pairs kept since.
TEST(SelfContactWorld, BodiesFlyingAsAWholeAreSearchedAgainstThemselvesOnce) {
  const Scene scene = read_scene(fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / "impact.json");
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  options.response = scene.response;
  World world(make_scene_bodies(scene, read_tetgen, 12), step_settings(scene.settings), options);
  std::uint64_t searches = 0, constraints = 0;
  for (int frame = 1; frame <= 12; ++frame) {
    world.step();
    const ResponseCounts c = world.response_counts();
    EXPECT_EQ(c.self_searches, frame == 1 ? 2u : 0u) << "frame " << frame;
    EXPECT_EQ(c.between_bodies, 0u) << "frame " << frame << ": the bodies are apart";
    searches += c.searches;
    constraints += c.vertex_face + c.edge_edge;
    EXPECT_TRUE(world.contacts().empty()) << "frame " << frame;
  }
  EXPECT_EQ(searches, 12u) << "one window a frame (nothing strays)";
  EXPECT_GT(constraints, 0u) << "the kept pairs are constraints";
}

// Turned off, the same bodies have no pair with themselves: apart, no constraint at all.
TEST(SelfContactWorld, SelfCollisionTurnedOffSearchesNoBodyAgainstItself) {
  const Scene scene = read_scene(fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / "impact.json");
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  options.self_collision = false;
  options.response = scene.response;
  World world(make_scene_bodies(scene, read_tetgen, 3), step_settings(scene.settings), options);
  for (int frame = 1; frame <= 3; ++frame) {
    world.step();
    const ResponseCounts c = world.response_counts();
    EXPECT_EQ(c.self_searches, 0u) << "frame " << frame;
    EXPECT_EQ(c.vertex_face + c.edge_edge, 0u) << "frame " << frame;
  }
}

}  // namespace
}  // namespace deformcd
