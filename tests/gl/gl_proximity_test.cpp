// The GL proximity search (src/gpu/gl/gl_proximity.h) against CpuProximity::find: the same
// candidates, in the same order, on crossing, separate and self-colliding grids, for several
// reaches. The GL search reads BVHs uploaded here as a GlCollision holds them (built and
// refitted on the host with the functions both backends share), positions in one vec4 buffer.

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "collision_test_worlds.h"
#include "core/collision/bvh.h"
#include "core/collision/proximity.h"
#include "cpu/cpu_proximity.h"
#include "cpu/executor.h"
#include "deformcd/error.h"
#include "deformcd/gl/ssbo.h"
#include "gl_test_context.h"
#include "gpu/gl/gl_collision.h"
#include "gpu/gl/gl_proximity.h"
#include "proximity_distance_filter.h"
#include "support/collision_fixtures.h"

namespace deformcd::gl {
namespace {

// A fixture's faces, meshes, BVHs (boxes refitted on its positions) and positions on the GPU.
struct GpuFixture {
  explicit GpuFixture(const test::CollisionFixture& f)
      : faces(std::span<const gpu::Face>(f.data.faces)),
        meshes(f.data.meshes.size()),
        bvh_nodes(std::span<const gpu::BvhNode>(f.data.bvh_nodes)),
        bvh_boxes(f.data.bvh_nodes.size()),
        mesh_bvhs(std::span<const gpu::BodyBvh>(f.data.mesh_bvhs)),
        positions(1) {
    std::vector<glm::vec4> all;
    std::vector<gpu::MeshInfo> infos = f.data.meshes;
    for (std::size_t m = 0; m < infos.size(); ++m) {
      infos[m].position_offset = 4u * static_cast<std::uint32_t>(all.size());
      infos[m].position_stride = 4u;
      all.insert(all.end(), f.positions[m].begin(), f.positions[m].end());
    }
    meshes.upload(std::span<const gpu::MeshInfo>(infos));
    positions = Ssbo<glm::vec4>(std::span<const glm::vec4>(all));
    std::vector<gpu::Box> boxes(f.data.bvh_nodes.size());
    for (const gpu::BodyBvh& tree : f.data.mesh_bvhs) {
      collision::refit_bvh(f.data.bvh_nodes, tree.root, tree.node_count, f.vertices(), f.data.faces,
                           boxes);
    }
    bvh_boxes.upload(std::span<const gpu::Box>(boxes));
  }

  [[nodiscard]] ProximitySources sources() const {
    return {positions.name(), faces.name(),     meshes.name(),
            bvh_nodes.name(), bvh_boxes.name(), mesh_bvhs.name()};
  }

  Ssbo<gpu::Face> faces;
  Ssbo<gpu::MeshInfo> meshes;
  Ssbo<gpu::BvhNode> bvh_nodes;
  Ssbo<gpu::Box> bvh_boxes;
  Ssbo<gpu::BodyBvh> mesh_bvhs;
  Ssbo<glm::vec4> positions;
};

class GlProximityTest : public test_support::GlTest {
 protected:
  // GL's list, through the CPU's distance filter (proximity_distance_filter.h), equals the
  // CPU's for each reach list, without motion (the GL search still sweeps per mesh, the CPU's
  // per vertex: the two agree when nothing moves); returns the list sizes.
  std::vector<std::size_t> expect_cpu_candidates(const test::CollisionFixture& f,
                                                 const std::vector<std::vector<float>>& reaches,
                                                 const std::string& where) {
    const GpuFixture gpu(f);
    GlProximity gl(context(), f.data);
    cpu::CpuProximity cpu(f.data, std::make_shared<cpu::Executor>(2));
    std::vector<std::size_t> sizes;
    for (const std::vector<float>& reach : reaches) {
      const std::vector<glm::vec3> drift(reach.size(), glm::vec3(0.0f));
      const std::vector<collision::ProximityCandidate> expected =
          cpu.find(f.vertices(), nullptr, test::reach_per_vertex(f.data, reach).get());
      const std::vector<collision::ProximityCandidate> boxed = gl.find(gpu.sources(), reach, drift);
      const std::vector<collision::ProximityCandidate> found =
          test::within_reach(boxed, f.vertices(), reach);
      EXPECT_GE(boxed.size(), found.size());
      EXPECT_EQ(found.size(), expected.size()) << where << ", reach " << reach[0];
      EXPECT_TRUE(found == expected) << where << ", reach " << reach[0];
      sizes.push_back(expected.size());
    }
    return sizes;
  }
};

TEST_F(GlProximityTest, CrossingGridsGiveTheCpuCandidates) {
  const test::CollisionFixture f = test::collision_fixture(test::two_crossing_grids());
  const std::vector<std::size_t> sizes = expect_cpu_candidates(
      f, {{0.0f, 0.0f}, {0.002f, 0.005f}, {0.02f, 0.01f}, {0.1f, 0.1f}}, "crossing grids");
  // With no reach only primitives that touch exactly count (the grids cross edge through face).
  EXPECT_LE(sizes[0], sizes[1]);
  EXPECT_GT(sizes[1], 0u);
  EXPECT_GT(sizes[2], sizes[1]) << "a longer reach finds more";
  EXPECT_GT(sizes[3], sizes[2]);
}

TEST_F(GlProximityTest, SeparateGridsGiveNoneUntilTheReachSpansTheGap) {
  const test::CollisionFixture f = test::collision_fixture(test::two_separate_grids());
  const std::vector<std::size_t> sizes =
      expect_cpu_candidates(f, {{0.01f, 0.01f}, {0.4f, 0.4f}}, "separate grids");
  EXPECT_EQ(sizes[0], 0u);
  EXPECT_GT(sizes[1], 0u);
}

// Self-proximity: within a mesh, faces sharing a corner are neighbours and left out, each
// pair once.
TEST_F(GlProximityTest, SelfProximityGivesTheCpuCandidates) {
  const test::CollisionFixture f = test::collision_fixture(test::two_crossing_grids(), true);
  ASSERT_EQ(f.data.mesh_pairs.size(), 3u);
  const std::vector<std::size_t> sizes =
      expect_cpu_candidates(f, {{0.005f, 0.005f}, {0.06f, 0.03f}}, "self");
  EXPECT_GT(sizes[1], sizes[0]);
}

// Plugged into a GlCollision: prepare_proximity refits its BVHs on the current positions and
// binds them, find_bound searches them. After the grids have moved (no detect() since), the
// list is the CPU's on the new positions, and the last pass's results are left as they were.
TEST_F(GlProximityTest, OverAGlCollisionsRefittedTreesGivesTheCpuCandidates) {
  test::CollisionFixture f = test::collision_fixture(test::two_crossing_grids(), true);
  GlCollision collision(context());
  collision.upload(f.data);
  collision.set_positions(f.host_sources());
  collision.detect(BroadPhase::kBvh);
  const gpu::CollisionCounters before = collision.counters();
  ASSERT_GT(before.face_pairs, 0u);
  GlProximity gl(context(), f.data);
  cpu::CpuProximity cpu(f.data, std::make_shared<cpu::Executor>(2));
  const std::vector<float> reach = {0.01f, 0.02f};
  for (int step = 0; step < 3; ++step) {
    if (step > 0) {
      // Mesh 1 slides and every vertex jitters: the trees must be refitted to find the pairs.
      for (std::size_t m = 0; m < f.positions.size(); ++m)
        for (std::size_t i = 0; i < f.positions[m].size(); ++i) {
          const auto n = static_cast<std::uint32_t>(i);
          f.positions[m][i] += glm::vec4(0.004f * test::hash_unit(n, 10u * step + 1u),
                                         0.004f * test::hash_unit(n, 10u * step + 2u),
                                         0.004f * test::hash_unit(n, 10u * step + 3u), 0.0f) +
                               (m == 1 ? glm::vec4(-0.03f, 0.0f, 0.0f, 0.0f) : glm::vec4(0.0f));
        }
    }
    collision.prepare_proximity();
    const std::vector<glm::vec3> drift(reach.size(), glm::vec3(0.0f));
    const std::vector<collision::ProximityCandidate> found =
        test::within_reach(gl.find_bound(reach, drift), f.vertices(), reach);
    const std::vector<collision::ProximityCandidate> expected =
        cpu.find(f.vertices(), nullptr, test::reach_per_vertex(f.data, reach).get());
    EXPECT_GT(expected.size(), 0u);
    EXPECT_EQ(found.size(), expected.size()) << "step " << step;
    EXPECT_TRUE(found == expected) << "step " << step;
  }
  const gpu::CollisionCounters after = collision.counters();
  EXPECT_EQ(after.face_pairs, before.face_pairs);
  EXPECT_EQ(after.candidates, before.candidates);
}

TEST_F(GlProximityTest, ReachListOfTheWrongLengthIsRefused) {
  const test::CollisionFixture f = test::collision_fixture(test::two_crossing_grids());
  const GpuFixture gpu(f);
  GlProximity gl(context(), f.data);
  const std::vector<float> one = {0.01f};
  const std::vector<glm::vec3> one_drift = {glm::vec3(0.0f)};
  EXPECT_THROW((void)gl.find(gpu.sources(), one, one_drift), Error);
}

}  // namespace
}  // namespace deformcd::gl
