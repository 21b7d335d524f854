// The GL proximity search (src/gpu/gl/gl_proximity.h) against CpuProximity::find over the same
// trees: the same
// candidates, in the same order, on crossing, separate and self-colliding grids, for reaches
// that vary from vertex to vertex, with and without motion (a drift per mesh plus a different
// jitter per vertex), so that the swept boxes, the grown boxes and the distance filter
// (closing speed, the float bound, the exact distance in double) all decide. The GL search
// reads BVHs uploaded here as a GlCollision holds them (built on the host with the functions
// both backends share), positions in one vec4 buffer; then a GlCollision's own.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/collision/primitive_distance.h"
#include "core/collision/proximity.h"
#include "core/collision/vertex_positions.h"
#include "cpu/cpu_proximity.h"
#include "cpu/executor.h"
#include "deformcd/detector.h"
#include "deformcd/error.h"
#include "deformcd/gl/ssbo.h"
#include "gl/collision_test_worlds.h"
#include "gl/gl_test_context.h"
#include "gl/proximity_vertex_lists.h"
#include "gpu/gl/bvh_work_order.h"
#include "gpu/gl/gl_collision.h"
#include "gpu/gl/gl_proximity.h"
#include "support/collision_fixtures.h"

namespace deformcd::gl {
namespace {

using test::vertex_lists;
using test::VertexLists;

// A fixture's faces, meshes, BVHs (with their refit order) and positions on the GPU.
struct GpuFixture {
  explicit GpuFixture(const test::CollisionFixture& f)
      : order(plan_bvh_work_order(f.data.bvh_nodes, f.data.mesh_bvhs, f.data.meshes,
                                  f.data.faces.size())),
        faces(std::span<const gpu::Face>(f.data.faces)),
        meshes(f.data.meshes.size()),
        bvh_nodes(std::span<const gpu::BvhNode>(f.data.bvh_nodes)),
        mesh_bvhs(std::span<const gpu::BodyBvh>(f.data.mesh_bvhs)),
        levels(std::span<const std::uint32_t>(order.refit_order)),
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
  }

  [[nodiscard]] ProximitySources sources() const {
    return {.positions = positions.name(),
            .faces = faces.name(),
            .meshes = meshes.name(),
            .bvh_nodes = bvh_nodes.name(),
            .mesh_bvhs = mesh_bvhs.name(),
            .refit = {.buffer = levels.name(), .levels = order.levels}};
  }

  BvhWorkOrder order;
  Ssbo<gpu::Face> faces;
  Ssbo<gpu::MeshInfo> meshes;
  Ssbo<gpu::BvhNode> bvh_nodes;
  Ssbo<gpu::BodyBvh> mesh_bvhs;
  Ssbo<std::uint32_t> levels;
  Ssbo<glm::vec4> positions;
};

class GlProximityTest : public test_support::GlTest {
 protected:
  // GL's list equals the CPU's for each set of vertex lists; returns the list sizes.
  std::vector<std::size_t> expect_cpu_candidates(const test::CollisionFixture& f,
                                                 const std::vector<VertexLists>& cases,
                                                 const std::string& where) {
    const GpuFixture gpu(f);
    GlProximity gl(context(), f.data);
    test::HostProximity cpu(f.data, f.vertices());
    const std::vector<std::uint32_t> pairs = collision::searched_mesh_pairs(f.data, {});
    std::vector<std::size_t> sizes;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const VertexLists& lists = cases[i];
      const std::vector<collision::ProximityCandidate> expected =
          cpu.search.find(f.vertices(), lists.cpu_motion(), lists.cpu_reach(), pairs);
      const std::vector<collision::ProximityCandidate> found =
          gl.find(gpu.sources(), lists.reach, lists.motion, pairs);
      EXPECT_EQ(found.size(), expected.size()) << where << ", case " << i;
      EXPECT_TRUE(found == expected) << where << ", case " << i;
      sizes.push_back(expected.size());
    }
    std::string listed;
    for (const std::size_t n : sizes)
      listed += (listed.empty() ? "" : ",") + std::to_string(n);
    RecordProperty("candidates_per_case", listed);
    return sizes;
  }
};

TEST_F(GlProximityTest, CrossingGridsGiveTheCpuCandidates) {
  const test::CollisionFixture f = test::collision_fixture(test::two_crossing_grids());
  const std::vector<glm::vec3> drift = {{0.01f, 0.0f, -0.004f}, {-0.008f, 0.006f, 0.0f}};
  std::vector<VertexLists> cases;
  for (const std::vector<float>& reach : std::vector<std::vector<float>>{
           {0.0f, 0.0f}, {0.002f, 0.005f}, {0.02f, 0.01f}, {0.1f, 0.1f}}) {
    cases.push_back(vertex_lists(f.data, reach));
    cases.push_back(vertex_lists(f.data, reach, drift, 0.004f));
  }
  const std::vector<std::size_t> sizes = expect_cpu_candidates(f, cases, "crossing grids");
  // With no reach and no motion only primitives that touch exactly count (the grids cross edge
  // through face).
  EXPECT_LE(sizes[0], sizes[2]);
  EXPECT_GT(sizes[2], 0u);
  EXPECT_GT(sizes[4], sizes[2]) << "a longer reach finds more";
  EXPECT_GT(sizes[6], sizes[4]);
  for (std::size_t i = 0; i < sizes.size(); i += 2)
    EXPECT_GE(sizes[i + 1], sizes[i]) << "moving vertices can come closer: a superset";
  EXPECT_GT(sizes[1], sizes[0]) << "the motion should matter";
}

// 1 m apart: nothing within a short reach, something within a long one or when mesh 1 moves
// through mesh 0; and nothing when both move together, though their swept boxes overlap (no
// closing speed: the distance filter rejects every pair the boxes let through).
TEST_F(GlProximityTest, SeparateGridsGiveNoneUntilTheReachOrTheMotionSpansTheGap) {
  const test::CollisionFixture f = test::collision_fixture(test::two_separate_grids());
  const std::vector<float> short_reach = {0.01f, 0.01f};
  const std::vector<glm::vec3> towards = {glm::vec3(0.0f), {-1.0f, 0.0f, 0.0f}};
  const std::vector<glm::vec3> together = {{1.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}};
  const std::vector<std::size_t> sizes = expect_cpu_candidates(
      f,
      {vertex_lists(f.data, short_reach), vertex_lists(f.data, std::vector<float>{0.4f, 0.4f}),
       vertex_lists(f.data, short_reach, towards, 0.002f),
       vertex_lists(f.data, short_reach, together)},
      "separate grids");
  EXPECT_EQ(sizes[0], 0u);
  EXPECT_GT(sizes[1], 0u);
  EXPECT_GT(sizes[2], 0u);
  EXPECT_EQ(sizes[3], 0u);
}

// Self-proximity: within a mesh, a vertex with a face it is a corner of and edges sharing a
// vertex are neighbours and left out (the other primitives of faces sharing a corner are
// pairs), each pair once.
TEST_F(GlProximityTest, SelfProximityGivesTheCpuCandidates) {
  const test::CollisionFixture f = test::collision_fixture(test::two_crossing_grids(), true);
  ASSERT_EQ(f.data.mesh_pairs.size(), 3u);
  const std::vector<glm::vec3> drift = {{0.0f, 0.01f, 0.0f}, {0.005f, 0.0f, 0.0f}};
  const std::vector<std::size_t> sizes = expect_cpu_candidates(
      f,
      {vertex_lists(f.data, std::vector<float>{0.005f, 0.005f}),
       vertex_lists(f.data, std::vector<float>{0.06f, 0.03f}),
       vertex_lists(f.data, std::vector<float>{0.01f, 0.02f}, drift, 0.01f, 5u)},
      "self");
  EXPECT_GT(sizes[1], sizes[0]);
  EXPECT_GT(sizes[2], 0u);
}

// Reaches on the border: each half of a candidate's own distance (rounded to float), so that
// the pair's exact squared distance in double is compared with a limit equal to that distance
// up to its rounding. Only bit-identical double arithmetic keeps the same pairs on both sides
// of so many borders; with motion, the closing speeds move the borders by float sums.
TEST_F(GlProximityTest, ReachesOnTheCandidatesOwnDistancesGiveTheCpuCandidates) {
  const test::CollisionFixture f = test::collision_fixture(test::two_crossing_grids(), true);
  test::HostProximity probe(f.data, f.vertices());
  const VertexLists wide = vertex_lists(f.data, std::vector<float>{0.03f, 0.03f});
  const std::vector<collision::ProximityCandidate> all = probe.search.find(
      f.vertices(), nullptr, wide.cpu_reach(), collision::searched_mesh_pairs(f.data, {}));
  ASSERT_GT(all.size(), 1000u);
  const std::vector<glm::vec3> drift = {{0.002f, 0.0f, 0.0f}, {0.0f, -0.002f, 0.0f}};
  std::vector<VertexLists> cases;
  for (std::size_t i = 0; i < all.size(); i += all.size() / 24u) {
    const collision::ProximityCandidate& c = all[i];
    const std::uint32_t first_b = c.kind == gpu::kContactEdgeEdge ? 2u : 1u;
    glm::vec3 x[4];
    for (std::uint32_t k = 0; k < 4u; ++k)
      x[k] = collision::vertex_position(f.vertices(), k < first_b ? c.mesh_a : c.mesh_b,
                                        c.vertices[k]);
    const float half = 0.5f * collision::primitive_distance(c.kind, x);
    VertexLists lists = wide;
    lists.reach.assign(wide.reach.size(), half);
    lists.repoint();
    cases.push_back(std::move(lists));
    cases.push_back(vertex_lists(f.data, std::vector<float>{half, half}, drift, 0.0005f,
                                 static_cast<std::uint32_t>(i)));
  }
  const std::vector<std::size_t> sizes = expect_cpu_candidates(f, cases, "border reaches");
  EXPECT_GT(*std::max_element(sizes.begin(), sizes.end()), 0u);
}

// The GL backend's proximity phase (GlCollision::find_proximity): it stages its positions and
// searches over its own trees with boxes of its own. After the grids have moved (no detect()
// since), the list is the host search's over the same trees on the new positions, with the
// vertices' motions and reaches changing too, and the last pass's results and boxes are left
// as they were. Widened on the host over the same trees (widen_proximity), the GL backend gives
// the host search's widening.
TEST_F(GlProximityTest, OverAGlCollisionsTreesGivesTheCpuCandidates) {
  test::CollisionFixture f = test::collision_fixture(test::two_crossing_grids(), true);
  GlCollision collision(context());
  collision.upload(f.data);
  collision.set_positions(f.host_sources());
  collision.detect(BroadPhase::kBvh);
  const gpu::CollisionCounters before = collision.counters();
  ASSERT_GT(before.face_pairs, 0u);
  std::vector<gpu::Box> boxes_before;
  collision.download_bvh_boxes(boxes_before);
  test::HostProximity cpu(f.data, f.vertices());
  const std::vector<std::uint32_t> pairs = collision::searched_mesh_pairs(f.data, {});
  for (std::uint32_t step = 0; step < 3; ++step) {
    if (step > 0) {
      // Mesh 1 slides and every vertex jitters: the boxes must be refitted to find the pairs.
      for (std::size_t m = 0; m < f.positions.size(); ++m)
        for (std::size_t i = 0; i < f.positions[m].size(); ++i) {
          const auto n = static_cast<std::uint32_t>(i);
          f.positions[m][i] += glm::vec4(0.004f * test::hash_unit(n, 10u * step + 1u),
                                         0.004f * test::hash_unit(n, 10u * step + 2u),
                                         0.004f * test::hash_unit(n, 10u * step + 3u), 0.0f) +
                               (m == 1 ? glm::vec4(-0.03f, 0.0f, 0.0f, 0.0f) : glm::vec4(0.0f));
        }
    }
    const std::vector<glm::vec3> drift = {{0.0f, 0.0f, 0.0f},
                                          {-0.01f * static_cast<float>(step), 0.0f, 0.0f}};
    VertexLists lists =
        vertex_lists(f.data, std::vector<float>{0.01f, 0.02f}, drift, 0.005f, 20u + step);
    std::vector<float> distances = {1.0f};
    const std::vector<collision::ProximityCandidate> found =
        collision.find_proximity(lists.query(f.vertices(), pairs), distances);
    EXPECT_TRUE(distances.empty()) << "GL leaves the distances to the caller";
    const std::vector<collision::ProximityCandidate> expected =
        cpu.search.find(f.vertices(), lists.cpu_motion(), lists.cpu_reach(), pairs);
    EXPECT_GT(expected.size(), 0u);
    EXPECT_EQ(found.size(), expected.size()) << "step " << step;
    EXPECT_TRUE(found == expected) << "step " << step;
    // Every tenth vertex of mesh 1 reaches twice as far.
    std::vector<std::array<std::uint32_t, 2>> widened;
    for (std::uint32_t v = 0; v < f.data.meshes[1].vertex_count; v += 10u) {
      widened.push_back({1u, v});
      lists.reach[lists.first[1] + v] *= 2.0f;
    }
    std::vector<float> widened_distances;
    const std::vector<collision::ProximityCandidate> found_widened =
        collision.widen_proximity(lists.query(f.vertices(), pairs), widened, widened_distances);
    std::vector<float> expected_distances;
    const std::vector<collision::ProximityCandidate> expected_widened = cpu.search.widen(
        f.vertices(), lists.cpu_motion(), lists.cpu_reach(), pairs, widened, expected_distances);
    EXPECT_GT(expected_widened.size(), 0u) << "step " << step;
    EXPECT_TRUE(found_widened == expected_widened) << "step " << step;
    EXPECT_TRUE(widened_distances == expected_distances) << "step " << step;
  }
  const gpu::CollisionCounters after = collision.counters();
  EXPECT_EQ(after.face_pairs, before.face_pairs);
  EXPECT_EQ(after.candidates, before.candidates);
  std::vector<gpu::Box> boxes_after;
  collision.download_bvh_boxes(boxes_after);
  ASSERT_EQ(boxes_after.size(), boxes_before.size());
  EXPECT_EQ(0, std::memcmp(boxes_after.data(), boxes_before.data(),
                           boxes_before.size() * sizeof(gpu::Box)))
      << "the search refits boxes of its own";
}

TEST_F(GlProximityTest, ListsOfTheWrongLengthAreRefused) {
  const test::CollisionFixture f = test::collision_fixture(test::two_crossing_grids());
  const GpuFixture gpu(f);
  GlProximity gl(context(), f.data);
  const VertexLists lists = vertex_lists(f.data, std::vector<float>{0.01f, 0.01f},
                                         std::vector<glm::vec3>(2, glm::vec3(0.0f)));
  const std::vector<float> short_reach(lists.reach.begin(), lists.reach.end() - 1);
  const std::vector<glm::vec3> short_motion(lists.motion.begin(), lists.motion.end() - 1);
  const std::vector<std::uint32_t> pairs = collision::searched_mesh_pairs(f.data, {});
  EXPECT_THROW((void)gl.find(gpu.sources(), short_reach, lists.motion, pairs), Error);
  EXPECT_THROW((void)gl.find(gpu.sources(), lists.reach, short_motion, pairs), Error);
  const std::vector<std::uint32_t> beyond = {static_cast<std::uint32_t>(f.data.mesh_pairs.size())};
  EXPECT_THROW((void)gl.find(gpu.sources(), lists.reach, lists.motion, beyond), Error);
  EXPECT_NO_THROW((void)gl.find(gpu.sources(), lists.reach, {}, pairs));
}

// Through the public Detector: on GL, find_proximity runs the GL search over the GL backend's
// trees and computes the distances from positions read back; its pairs, and a widening's,
// equal the CPU detector's field for field (order and distances included), with a reach per
// vertex or per mesh, with and without motion, with positions in host arrays and in a GL
// buffer, after the positions move without a detect(), and the GL detector's contacts are not
// disturbed.
TEST_F(GlProximityTest, DetectorOnGlEqualsTheCpuDetector) {
  test::CollisionFixture f = test::collision_fixture(test::two_crossing_grids(), true);
  const std::vector<CollisionMesh> meshes = test::surface_meshes(test::two_crossing_grids(), true);
  Detector gl_detector(meshes, {.backend = BackendKind::kGl, .gl_context = &context()});
  Detector cpu_detector(meshes, {.backend = BackendKind::kCpu, .threads = 2});
  ASSERT_EQ(gl_detector.backend_name(), "gl");
  std::vector<std::vector<glm::vec3>> host(f.positions.size());
  std::vector<glm::vec4> all;
  for (std::size_t m = 0; m < f.positions.size(); ++m) {
    for (const glm::vec4& p : f.positions[m])
      host[m].emplace_back(p);
    all.insert(all.end(), f.positions[m].begin(), f.positions[m].end());
  }
  Ssbo<glm::vec4> buffer{std::span<const glm::vec4>(all)};
  for (std::size_t m = 0; m < host.size(); ++m) {
    gl_detector.set_positions(m, std::span<const glm::vec3>(host[m]));
    cpu_detector.set_positions(m, std::span<const glm::vec3>(host[m]));
  }
  const std::vector<glm::vec3> drift = {{0.004f, 0.0f, 0.0f}, {-0.006f, 0.002f, 0.0f}};
  const auto moving_vertex_count = static_cast<std::uint32_t>(all.size());
  const auto expect_same = [&](const std::vector<float>& reach,
                               const std::vector<glm::vec3>& motion, const std::string& where) {
    const std::vector<ProximityPair> expected = cpu_detector.find_proximity(reach, motion);
    const std::vector<ProximityPair> found = gl_detector.find_proximity(reach, motion);
    EXPECT_GT(expected.size(), 0u) << where;
    EXPECT_EQ(found.size(), expected.size()) << where;
    EXPECT_TRUE(found == expected) << where;
    // Every seventh vertex (over both meshes) reaching 3 cm: the widenings agree too.
    std::vector<std::uint32_t> vertices;
    for (std::uint32_t v = 0; v < moving_vertex_count; v += 7u)
      vertices.push_back(v);
    const std::vector<float> raised(vertices.size(), 0.03f);
    const std::vector<ProximityPair> widened = cpu_detector.widen_proximity(vertices, raised);
    EXPECT_GT(widened.size(), 0u) << where;
    EXPECT_TRUE(gl_detector.widen_proximity(vertices, raised) == widened) << where;
  };
  const VertexLists moving =
      vertex_lists(f.data, std::vector<float>{0.01f, 0.015f}, drift, 0.003f, 3u);
  expect_same(moving.reach, moving.motion, "host positions, per vertex, moving");
  expect_same({0.01f, 0.02f}, {}, "host positions, per mesh, still");
  // Still meshes: GL searches the mesh pairs the CPU does (mesh 0 still: its pair with itself
  // is not searched; both still: none is), then all of them again.
  for (const std::vector<std::uint8_t>& still :
       {std::vector<std::uint8_t>{1u, 0u}, std::vector<std::uint8_t>{1u, 1u}}) {
    const std::vector<ProximityPair> some =
        cpu_detector.find_proximity(moving.reach, moving.motion, still);
    EXPECT_EQ(some.empty(), still[1] != 0u);
    EXPECT_TRUE(gl_detector.find_proximity(moving.reach, moving.motion, still) == some);
  }
  expect_same(moving.reach, moving.motion, "host positions, per vertex, moving, after subsets");
  const std::vector<std::uint8_t> one_flag = {1u};
  EXPECT_THROW((void)gl_detector.find_proximity(moving.reach, moving.motion, one_flag), InputError);

  // The same positions in a GL buffer (vec4 per vertex), then moved there and in the host
  // arrays alike; the GL detector detects in between.
  gl_detector.detect();
  // Each contact's faces and segment, to compare the passes' results.
  const auto faces_of = [](const std::vector<Contact>& list) {
    std::vector<std::array<float, 10>> out;
    out.reserve(list.size());
    for (const Contact& c : list)
      out.push_back({static_cast<float>(c.a.body), static_cast<float>(c.a.face),
                     static_cast<float>(c.b.body), static_cast<float>(c.b.face), c.segment[0].x,
                     c.segment[0].y, c.segment[0].z, c.segment[1].x, c.segment[1].y,
                     c.segment[1].z});
    return out;
  };
  const auto contacts = faces_of(gl_detector.contacts());
  ASSERT_FALSE(contacts.empty());
  std::size_t first = 0;
  for (std::size_t m = 0; m < host.size(); ++m) {
    gl_detector.set_positions(
        m, GlPositions{buffer.name(), first * sizeof(glm::vec4), sizeof(glm::vec4)});
    first += host[m].size();
  }
  expect_same(moving.reach, moving.motion, "GL buffer, per vertex, moving");
  EXPECT_TRUE(faces_of(gl_detector.contacts()) == contacts)
      << "the search leaves the last pass alone";
  for (std::size_t m = 0, i = 0; m < host.size(); ++m)
    for (glm::vec3& p : host[m]) {
      p += glm::vec3(m == 1 ? -0.02f : 0.0f,
                     0.003f * test::hash_unit(static_cast<std::uint32_t>(i), 9u), 0.0f);
      all[i++] = glm::vec4(p, 1.0f);
    }
  buffer.upload(std::span<const glm::vec4>(all));
  expect_same(moving.reach, moving.motion, "GL buffer moved, per vertex, moving");
}

}  // namespace
}  // namespace deformcd::gl
