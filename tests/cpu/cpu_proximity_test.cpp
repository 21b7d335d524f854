// CpuProximity::find against its plainest form: each face of each mesh pair's first mesh
// queries the other mesh's tree from the root (the GL search's work items, in its order), and
// the candidates of every face pair it meets follow in turn. find() descends both trees together
// and restores that order; it must give exactly that list, distances included, on one thread
// and on two.

#include "cpu/cpu_proximity.h"

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "core/collision/bvh.h"
#include "core/collision/bvh_upkeep.h"
#include "core/collision/proximity.h"
#include "cpu/executor.h"
#include "support/collision_fixtures.h"
#include "support/world_fixtures.h"

namespace deformcd::cpu {
namespace {

BodyInit grid_body(int n, double spacing, glm::dvec3 origin) {
  BodyInit init;
  init.body = build_body(test::tet_grid(n, n, n, spacing, origin));
  return init;
}

struct Search {
  std::vector<collision::ProximityCandidate> candidates;
  std::vector<float> distances;
};

// One query per face, as find() documents its order (and as CpuProximity searched before the
// trees were descended together).
Search query_per_face(const collision::BvhUpkeep& trees, const std::vector<gpu::BodyPair>& pairs,
                      collision::VertexPositions positions, collision::VertexPositions motion,
                      collision::VertexReach reach) {
  const std::vector<gpu::Face>& faces = trees.faces();
  std::vector<collision::SweptFace> swept;
  for (const gpu::Face& f : faces)
    swept.push_back(collision::sweep_face(positions, motion, reach, f));
  const std::vector<gpu::BvhNode>& nodes = trees.nodes();
  std::vector<gpu::Box> boxes(nodes.size());
  for (const gpu::BodyBvh& tree : trees.trees()) {
    for (std::uint32_t i = tree.root + tree.node_count; i-- > tree.root;) {
      const gpu::BvhNode& n = nodes[i];
      if (n.face != gpu::kBvhInternal) {
        boxes[i] = swept[n.face].box;
      } else {
        boxes[i] = {glm::min(boxes[n.left].min, boxes[n.right].min),
                    glm::max(boxes[n.left].max, boxes[n.right].max)};
      }
    }
  }
  const std::vector<std::uint32_t> owners = collision::primitive_owners(faces);
  Search out;
  for (const gpu::BodyPair& pair : pairs) {
    const gpu::MeshInfo& mesh_a = trees.meshes()[pair.a];
    for (std::uint32_t a = mesh_a.face_offset; a < mesh_a.face_offset + mesh_a.face_count; ++a) {
      collision::query_bvh(
          nodes.data(), boxes.data(), trees.tree(pair.b).root, swept[a].box, [&](std::uint32_t b) {
            if (pair.a == pair.b && b <= a) return;
            collision::emit_face_pair_candidates(
                faces[a], swept[a], collision::sweep_primitives(swept[a]), a, owners[a], faces[b],
                swept[b], collision::sweep_primitives(swept[b]), b, owners[b],
                [&](const collision::ProximityCandidate& c, float distance) {
                  out.candidates.push_back(c);
                  out.distances.push_back(distance);
                });
          });
    }
  }
  return out;
}

TEST(CpuProximity, FindGivesOneQueryPerFacesCandidatesInItsOrder) {
  // Three grids, 0 and 1 and 1 and 2 interpenetrating, each also against itself; grid 1 bent
  // so that its surface comes within reach of itself away from its neighbours.
  test::CollisionFixture f = test::collision_fixture(
      {grid_body(4, 0.25, glm::dvec3(0.0)), grid_body(5, 0.21, glm::dvec3(0.63, 0.31, 0.17)),
       grid_body(3, 0.3, glm::dvec3(1.41, 0.52, 0.45))},
      true);
  for (glm::vec4& p : f.positions[1])
    p.y += 0.3f * std::sin(4.0f * p.x) * std::cos(3.0f * p.z);
  ASSERT_GE(f.data.mesh_pairs.size(), 5u);
  collision::BvhUpkeep trees;
  trees.reset(f.data, f.vertices());
  // A reach and a motion per vertex, different from vertex to vertex.
  std::vector<std::vector<float>> reach_of;
  std::vector<std::vector<glm::vec4>> motion_of;
  for (const std::vector<glm::vec4>& mesh : f.positions) {
    std::vector<float>& reach = reach_of.emplace_back();
    std::vector<glm::vec4>& motion = motion_of.emplace_back();
    for (std::size_t v = 0; v < mesh.size(); ++v) {
      const float i = static_cast<float>(v);
      reach.push_back(0.02f * (1.0f + 0.5f * std::sin(1.3f * i)));
      motion.emplace_back(0.03f * std::sin(0.7f * i), -0.02f * std::cos(0.4f * i), 0.01f, 0.0f);
    }
  }
  std::vector<const float*> reach;
  std::vector<collision::MeshVertices> motion;
  for (std::size_t m = 0; m < reach_of.size(); ++m) {
    reach.push_back(reach_of[m].data());
    motion.push_back({&motion_of[m][0].x, 4u});
  }
  std::vector<std::uint32_t> all_pairs;
  for (std::uint32_t p = 0; p < f.data.mesh_pairs.size(); ++p)
    all_pairs.push_back(p);

  const Search expected =
      query_per_face(trees, f.data.mesh_pairs, f.vertices(), motion.data(), reach.data());
  ASSERT_GT(expected.candidates.size(), 500u) << "the grids should be within reach";
  for (const int threads : {1, 2}) {
    CpuProximity search(trees, f.data.mesh_pairs, std::make_shared<Executor>(threads));
    std::vector<float> distances;
    const std::vector<collision::ProximityCandidate> found =
        search.find(f.vertices(), motion.data(), reach.data(), all_pairs, &distances);
    EXPECT_TRUE(found == expected.candidates) << threads << " thread(s)";
    EXPECT_TRUE(distances == expected.distances) << threads << " thread(s)";
  }
}

}  // namespace
}  // namespace deformcd::cpu
