// The CPU collision backend against the plainest oracle: the narrow phase over every face pair.
// Every broad phase (brute, octree, octree-compact, bvh) must return exactly its pairs.

#include "cpu/cpu_collision.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <set>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "core/collision/broad_phase.h"
#include "core/collision/collision_data.h"
#include "core/collision/face_pair_intersection.h"
#include "core/collision/tri_tri_intersection.h"
#include "core/collision/vertex_positions.h"
#include "support/collision_fixtures.h"
#include "support/face_box_overlaps.h"
#include "support/world_fixtures.h"

namespace deformcd::cpu {
namespace {

using PairSet = std::set<std::pair<std::uint32_t, std::uint32_t>>;
using test::CollisionFixture;

BodyInit grid_body(int n, double spacing, glm::dvec3 origin) {
  BodyInit init;
  init.body = build_body(test::tet_grid(n, n, n, spacing, origin));
  return init;
}

// Every face pair of every mesh pair through the narrow phase: what any broad phase must
// return. Faces of different meshes take tri_tri_intersect; a mesh paired with itself takes
// every pair i < j of its faces not sharing an edge through face_pair_intersect.
PairSet all_pairs_oracle(const collision::CollisionData& d, collision::VertexPositions positions) {
  PairSet found;
  for (const gpu::BodyPair& bp : d.mesh_pairs) {
    const gpu::MeshInfo& a = d.meshes[bp.a];
    const gpu::MeshInfo& b = d.meshes[bp.b];
    for (std::uint32_t i = a.face_offset; i < a.face_offset + a.face_count; ++i) {
      for (std::uint32_t j = b.face_offset; j < b.face_offset + b.face_count; ++j) {
        const gpu::Face& fa = d.faces[i];
        const gpu::Face& fb = d.faces[j];
        if (bp.a == bp.b) {
          if (j <= i || collision::shared_nodes(fa, fb).count >= 2) continue;
          if (collision::face_pair_intersect(fa, fb, positions).intersect) found.insert({i, j});
          continue;
        }
        glm::vec3 p[3];
        glm::vec3 q[3];
        collision::face_vertices(positions, fa, p);
        collision::face_vertices(positions, fb, q);
        if (collision::tri_tri_intersect(p, q).intersect) found.insert({i, j});
      }
    }
  }
  return found;
}

PairSet all_pairs_oracle(const CollisionFixture& f) {
  return all_pairs_oracle(f.data, f.vertices());
}

struct Detected {
  PairSet pairs;
  std::size_t raw_count = 0;  // before removing duplicates: must equal pairs.size()
  std::vector<std::uint32_t> flags;
  gpu::CollisionCounters counters{};
};

// A backend over the fixture's data, reading its positions in place.
std::unique_ptr<CpuCollision> backend(const CollisionFixture& f, int threads = 0) {
  auto collision = std::make_unique<CpuCollision>(threads);
  collision->set_positions(f.host_sources());
  collision->upload(f.data);
  return collision;
}

Detected detect(const CollisionFixture& f, BroadPhase method, int threads = 0) {
  const std::unique_ptr<CpuCollision> collision = backend(f, threads);
  collision->detect(method);
  Detected d;
  std::vector<gpu::FacePair> raw;
  collision->download_face_pairs(raw);
  d.raw_count = raw.size();
  for (const gpu::FacePair& p : raw)
    d.pairs.insert({p.face_a, p.face_b});
  collision->download_face_flags(d.flags);
  d.counters = collision->counters();
  return d;
}

PairSet pair_set(const std::vector<gpu::FacePair>& raw) {
  PairSet set;
  for (const gpu::FacePair& p : raw)
    set.insert({p.face_a, p.face_b});
  return set;
}

std::vector<gpu::FacePair> raw_pairs(const CollisionFixture& f, BroadPhase method, int threads) {
  const std::unique_ptr<CpuCollision> collision = backend(f, threads);
  collision->detect(method);
  std::vector<gpu::FacePair> raw;
  collision->download_face_pairs(raw);
  return raw;
}

// Empty when the two raw lists are equal element by element, segments bit for bit.
std::string difference(const std::vector<gpu::FacePair>& x, const std::vector<gpu::FacePair>& y) {
  if (x.size() != y.size()) return std::to_string(x.size()) + " vs " + std::to_string(y.size());
  const auto key = [](const gpu::FacePair& p) {
    return std::tie(p.face_a, p.face_b, p.coplanar, p.segment0.x, p.segment0.y, p.segment0.z,
                    p.segment1.x, p.segment1.y, p.segment1.z);
  };
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (key(x[i]) != key(y[i])) return "pair " + std::to_string(i) + " differs";
  }
  return "";
}

// Mirrors the vertices of mesh `mesh` below its middle height through its middle x plane, then
// those left of it through its middle z plane: quarters turn inside out (their surfaces
// crossing the others'), so the siblings of a tree built on the unfolded shape overlap
// everywhere. In place: a backend reading the arrays sees the fold on its next detect().
void fold_quarters(CollisionFixture& f, std::uint32_t mesh) {
  std::vector<glm::vec4>& positions = f.positions[mesh];
  glm::vec3 lo(std::numeric_limits<float>::max());
  glm::vec3 hi(std::numeric_limits<float>::lowest());
  for (const glm::vec4& p : positions) {
    lo = glm::min(lo, glm::vec3(p));
    hi = glm::max(hi, glm::vec3(p));
  }
  const glm::vec3 mid = 0.5f * (lo + hi);
  for (glm::vec4& p : positions) {
    if (p.y < mid.y) p.x = 2.0f * mid.x - p.x;
    if (p.x < mid.x) p.z = 2.0f * mid.z - p.z;
  }
}

// Three grids: 0 and 1 interpenetrate, 1 and 2 interpenetrate, 0 and 2 are apart. Spacings
// differ so that faces cross at general angles of the grid lines.
std::vector<BodyInit> three_grids() {
  return {grid_body(4, 0.25, glm::dvec3(0.0)), grid_body(5, 0.21, glm::dvec3(0.63, 0.31, 0.17)),
          grid_body(3, 0.3, glm::dvec3(1.41, 0.52, 0.45))};
}

CollisionFixture three_bodies() {
  return test::collision_fixture(three_grids());
}

// The fixture of `bodies` with its data laid out from `meshes` (their surfaces, edited) and
// `pairs`, hierarchies built on the bodies' positions.
CollisionFixture fixture_of(const std::vector<BodyInit>& bodies,
                            const std::vector<CollisionMesh>& meshes,
                            const std::vector<MeshPair>* pairs) {
  CollisionFixture f = test::collision_fixture(bodies);
  f.data = collision::lay_out_meshes(meshes, pairs);
  collision::build_hierarchies(f.data, f.vertices());
  return f;
}

// The mesh a face (an index over every mesh) belongs to.
std::uint32_t mesh_of(const CollisionFixture& f, std::uint32_t face) {
  return f.data.faces[face].body;
}

constexpr BroadPhase kMethods[] = {BroadPhase::kBrute, BroadPhase::kOctree,
                                   BroadPhase::kOctreeCompact, BroadPhase::kBvh};

TEST(CpuCollision, EveryMethodReturnsExactlyTheOraclePairs) {
  const CollisionFixture w = three_bodies();
  const PairSet oracle = all_pairs_oracle(w);
  ASSERT_GT(oracle.size(), 20u);
  for (BroadPhase method : kMethods) {
    const Detected d = detect(w, method);
    EXPECT_EQ(d.pairs, oracle) << broadphase_name(method);
    EXPECT_EQ(d.raw_count, oracle.size()) << "a pair reported twice by " << broadphase_name(method);
    EXPECT_EQ(d.counters.face_pairs, oracle.size());
    // Flags: exactly the faces in some pair.
    std::set<std::uint32_t> faces;
    for (const auto& [a, b] : oracle) {
      faces.insert(a);
      faces.insert(b);
    }
    ASSERT_EQ(d.flags.size(), w.data.faces.size());
    for (std::uint32_t f = 0; f < d.flags.size(); ++f)
      EXPECT_EQ(d.flags[f] != 0u, faces.count(f) == 1) << f;
    EXPECT_EQ(d.counters.colliding_faces, faces.size());
  }
  // Meshes 0 and 2 are apart: no pair between them.
  const std::uint32_t mesh2_first_face = w.data.meshes[2].face_offset;
  for (const auto& [a, b] : oracle)
    EXPECT_FALSE(a < w.data.meshes[1].face_offset && b >= mesh2_first_face);
}

TEST(CpuCollision, OctreeCountsOverlappingLeafBoxPairs) {
  const CollisionFixture w = three_bodies();
  const Detected octree = detect(w, BroadPhase::kOctree);
  EXPECT_GT(octree.counters.box_pairs, 0u);
  EXPECT_LT(octree.counters.box_pairs, 3u * 64u * 64u);
  EXPECT_EQ(detect(w, BroadPhase::kOctreeCompact).counters.box_pairs, octree.counters.box_pairs);
  EXPECT_EQ(detect(w, BroadPhase::kBrute).counters.box_pairs, 0u);
  EXPECT_EQ(detect(w, BroadPhase::kBvh).counters.box_pairs, 0u);
}

TEST(CpuCollision, CandidatesCountTheTriangleTestsRun) {
  const CollisionFixture w = three_bodies();
  std::uint64_t all = 0;
  for (const gpu::BodyPair& bp : w.data.mesh_pairs)
    all += std::uint64_t{w.data.meshes[bp.a].face_count} * w.data.meshes[bp.b].face_count;
  const Detected brute = detect(w, BroadPhase::kBrute);
  const Detected octree = detect(w, BroadPhase::kOctree);
  const Detected compact = detect(w, BroadPhase::kOctreeCompact);
  const Detected bvh = detect(w, BroadPhase::kBvh);
  EXPECT_EQ(brute.counters.candidates, all);
  // The same first-box-pair rule picks the same tests; only the sweep that finds them differs.
  EXPECT_EQ(compact.counters.candidates, octree.counters.candidates);
  // One face per leaf: the bvh tests exactly the pairs whose own boxes overlap.
  EXPECT_EQ(bvh.counters.candidates, test::face_box_overlaps(w.data, w.vertices()));
  EXPECT_LT(bvh.counters.candidates, octree.counters.candidates);
  EXPECT_LT(octree.counters.candidates, brute.counters.candidates);
  EXPECT_GE(bvh.counters.candidates, bvh.counters.face_pairs);
}

TEST(CpuCollision, BodiesApartHaveNoContactsAndNoBoxPairs) {
  const CollisionFixture w = test::collision_fixture(
      {grid_body(3, 0.3, glm::dvec3(0.0)), grid_body(3, 0.3, glm::dvec3(2.0))});
  for (BroadPhase method : kMethods) {
    const Detected d = detect(w, method);
    EXPECT_TRUE(d.pairs.empty());
    EXPECT_EQ(d.counters.box_pairs, 0u);
    EXPECT_EQ(std::count(d.flags.begin(), d.flags.end(), 0u), static_cast<long>(d.flags.size()));
    if (method != BroadPhase::kBrute) {
      EXPECT_EQ(d.counters.candidates, 0u) << broadphase_name(method);
    }
  }
}

TEST(CpuCollision, OneBodyHasNoPairsToTest) {
  const CollisionFixture w = test::collision_fixture({grid_body(3, 0.3, glm::dvec3(0.0))});
  EXPECT_TRUE(w.data.mesh_pairs.empty());
  for (BroadPhase method : kMethods)
    EXPECT_TRUE(detect(w, method).pairs.empty());
}

TEST(CpuCollision, RawPairsAreOneListForEveryThreadCountAndMethod) {
  const CollisionFixture w = three_bodies();
  const std::vector<gpu::FacePair> reference = raw_pairs(w, BroadPhase::kBrute, 1);
  ASSERT_GT(reference.size(), 20u);
  for (BroadPhase method : kMethods) {
    for (int threads : {1, 2}) {
      EXPECT_EQ(difference(raw_pairs(w, method, threads), reference), "")
          << broadphase_name(method) << " on " << threads << " threads";
    }
  }
}

TEST(CpuCollision, BvhRebuildsADegradedTreeAndStillFindsThePairs) {
  CollisionFixture w = three_bodies();
  const PairSet rest_oracle = all_pairs_oracle(w);
  // The trees are built and fitted on the rest pose.
  const std::unique_ptr<CpuCollision> collision = backend(w);
  collision->detect(BroadPhase::kBvh);
  EXPECT_EQ(collision->bvh_trees().rebuild_count(), 0u);

  // Mesh 1 has the most faces: its tree is the one both of its pairs traverse. Folded in place,
  // the backend reads the new positions on its next pass.
  fold_quarters(w, 1);
  collision->detect(BroadPhase::kBvh);
  const BvhTrees& trees = collision->bvh_trees();
  EXPECT_EQ(trees.rebuild_count(), 1u);
  // Measured on the refitted tree, the fold loosened it past the threshold; the rebuilt tree
  // is the reference from now on.
  EXPECT_EQ(trees.area_ratio(1), trees.built_area_ratio(1));
  std::vector<gpu::FacePair> bvh;
  collision->download_face_pairs(bvh);
  const PairSet oracle = all_pairs_oracle(w);
  ASSERT_NE(oracle, rest_oracle);
  EXPECT_EQ(pair_set(bvh), oracle);
  collision->detect(BroadPhase::kBrute);
  std::vector<gpu::FacePair> brute;
  collision->download_face_pairs(brute);
  EXPECT_EQ(difference(bvh, brute), "");

  // The same shape again: the fresh tree is as tight as it gets, no second rebuild.
  collision->detect(BroadPhase::kBvh);
  EXPECT_EQ(collision->bvh_trees().rebuild_count(), 1u);
  std::vector<gpu::FacePair> again;
  collision->download_face_pairs(again);
  EXPECT_EQ(difference(again, brute), "");
}

TEST(CpuCollision, BvhLeavesATreeNobodyTraversesAsItIs) {
  CollisionFixture w = three_bodies();
  // The trees are built and fitted on the rest pose, then mesh 2 is folded in place. Mesh 2
  // has the fewest faces: the rebuild policy (the GL backend's, whose faces of the smaller mesh
  // query the larger one's tree) leaves its tree as it is; the CPU descends it all the same,
  // and every box in it is exact however loose the tree.
  const std::unique_ptr<CpuCollision> cpu = backend(w);
  fold_quarters(w, 2);
  cpu->detect(BroadPhase::kBvh);
  EXPECT_GT(cpu->bvh_trees().area_ratio(2),
            collision::kBvhRebuildFactor * cpu->bvh_trees().built_area_ratio(2));
  EXPECT_EQ(cpu->bvh_trees().rebuild_count(), 0u);
  std::vector<gpu::FacePair> bvh;
  cpu->download_face_pairs(bvh);
  const PairSet oracle = all_pairs_oracle(w);
  EXPECT_EQ(pair_set(bvh), oracle);
  // The folded mesh still crosses mesh 1: its faces did query mesh 1's tree.
  EXPECT_TRUE(std::any_of(oracle.begin(), oracle.end(), [&](const auto& pair) {
    return pair.second >= w.data.meshes[2].face_offset;
  }));
}

TEST(CpuCollision, LeafBoxesHoldTheirFacesCurrentVertices) {
  const CollisionFixture w = three_bodies();
  const std::unique_ptr<CpuCollision> collision = backend(w);
  collision->detect(BroadPhase::kOctree);
  std::vector<gpu::Box> boxes;
  collision->download_boxes(boxes);
  ASSERT_EQ(boxes.size(), 3u * 64u);
  for (const gpu::BoxFace& row : w.data.box_faces) {
    const gpu::Face& f = w.data.faces[row.face];
    const gpu::Box& b = boxes[64u * f.body + row.box];
    for (std::uint32_t n : {f.a, f.b, f.c}) {
      const glm::vec3 p = collision::vertex_position(w.vertices(), f.body, n);
      EXPECT_TRUE(glm::all(glm::lessThanEqual(glm::vec3(b.min), p)));
      EXPECT_TRUE(glm::all(glm::lessThanEqual(p, glm::vec3(b.max))));
    }
  }
}

TEST(CpuCollision, AMeshPairLeftOutOfTheListHasNoContactsOnAnyMethod) {
  const std::vector<BodyInit> bodies = three_grids();
  const std::vector<CollisionMesh> meshes = test::surface_meshes(bodies);
  // Every pair but (0, 1), which interpenetrates; (2, 1) is listed the other way round.
  const std::vector<MeshPair> listed = {{2, 1}, {0, 2}};
  const CollisionFixture w = fixture_of(bodies, meshes, &listed);
  ASSERT_EQ(w.data.mesh_pairs.size(), 2u);
  const CollisionFixture all = three_bodies();
  const PairSet every_pair = all_pairs_oracle(all);
  PairSet expected;
  std::size_t left_out = 0;
  for (const auto& [a, b] : every_pair) {
    const bool between_0_and_1 = mesh_of(all, a) == 0u && mesh_of(all, b) == 1u;
    left_out += between_0_and_1 ? 1u : 0u;
    if (!between_0_and_1) expected.insert({a, b});
  }
  ASSERT_GT(left_out, 0u) << "meshes 0 and 1 must interpenetrate for the test to mean anything";
  ASSERT_GT(expected.size(), 0u) << "meshes 1 and 2 must interpenetrate";
  ASSERT_EQ(all_pairs_oracle(w), expected);
  std::set<std::uint32_t> faces;
  for (const auto& [a, b] : expected) {
    faces.insert(a);
    faces.insert(b);
  }
  const std::uint64_t listed_candidates =
      std::uint64_t{w.data.meshes[0].face_count} * w.data.meshes[2].face_count +
      std::uint64_t{w.data.meshes[1].face_count} * w.data.meshes[2].face_count;
  for (BroadPhase method : kMethods) {
    const Detected d = detect(w, method);
    EXPECT_EQ(d.pairs, expected) << broadphase_name(method);
    EXPECT_EQ(d.raw_count, expected.size()) << broadphase_name(method);
    for (const auto& [a, b] : d.pairs)
      EXPECT_FALSE(mesh_of(w, a) == 0u && mesh_of(w, b) == 1u) << broadphase_name(method);
    // No face is flagged for a contact of the pair left out.
    for (std::uint32_t f = 0; f < d.flags.size(); ++f)
      EXPECT_EQ(d.flags[f] != 0u, faces.count(f) == 1) << broadphase_name(method) << " " << f;
    EXPECT_EQ(d.counters.colliding_faces, faces.size()) << broadphase_name(method);
    if (method == BroadPhase::kBrute) {
      EXPECT_EQ(d.counters.candidates, listed_candidates);
    } else if (method == BroadPhase::kBvh) {
      EXPECT_EQ(d.counters.candidates, test::face_box_overlaps(w.data, w.vertices()));
    }
  }
}

TEST(CpuCollision, AMeshWithSelfCollisionFindsItsOwnPairsOnEveryMethod) {
  // Two crossing grids, both folded into themselves; only mesh 0 collides with itself.
  const std::vector<BodyInit> bodies = {grid_body(4, 0.25, glm::dvec3(0.0)),
                                        grid_body(5, 0.21, glm::dvec3(0.63, 0.31, 0.17))};
  std::vector<CollisionMesh> meshes = test::surface_meshes(bodies);
  meshes[0].self_collision = true;
  CollisionFixture w = fixture_of(bodies, meshes, nullptr);
  ASSERT_EQ(w.data.mesh_pairs.size(), 2u);
  EXPECT_EQ(w.data.mesh_pairs[0].a, 0u);
  EXPECT_EQ(w.data.mesh_pairs[0].b, 0u);
  EXPECT_EQ(w.data.mesh_pairs[1].a, 0u);
  EXPECT_EQ(w.data.mesh_pairs[1].b, 1u);
  // The hierarchies stay those of the rest pose: the backend refits (and rebuilds) them.
  fold_quarters(w, 0);
  fold_quarters(w, 1);
  const PairSet expected = all_pairs_oracle(w);
  std::size_t self_pairs = 0;
  std::size_t sharing_a_node = 0;
  for (const auto& [a, b] : expected) {
    if (mesh_of(w, a) != mesh_of(w, b)) continue;
    ++self_pairs;
    sharing_a_node +=
        collision::shared_nodes(w.data.faces[a], w.data.faces[b]).count == 1 ? 1u : 0u;
  }
  ASSERT_GT(self_pairs, 20u);
  ASSERT_GT(expected.size(), self_pairs) << "the meshes must also cross each other";
  // Mesh 1 crosses itself too, but is not tested against itself.
  collision::CollisionData mesh1_with_itself = w.data;
  mesh1_with_itself.mesh_pairs = {{1u, 1u}};
  ASSERT_GT(all_pairs_oracle(mesh1_with_itself, w.vertices()).size(), 0u);
  for (BroadPhase method : kMethods) {
    const Detected d = detect(w, method);
    EXPECT_EQ(d.pairs, expected) << broadphase_name(method);
    EXPECT_EQ(d.raw_count, expected.size())
        << "a pair reported twice by " << broadphase_name(method);
    EXPECT_EQ(d.counters.face_pairs, expected.size());
    for (const auto& [a, b] : d.pairs) {
      EXPECT_LT(a, b);
      EXPECT_FALSE(mesh_of(w, a) == 1u && mesh_of(w, b) == 1u) << broadphase_name(method);
      EXPECT_LT(collision::shared_nodes(w.data.faces[a], w.data.faces[b]).count, 2)
          << "faces " << a << " and " << b << " share an edge";
    }
  }
  // Brute force tests the N (N - 1) / 2 pairs of mesh 0 and the N x M pairs with mesh 1.
  const std::uint64_t n = w.data.meshes[0].face_count;
  const std::uint64_t m = w.data.meshes[1].face_count;
  EXPECT_EQ(detect(w, BroadPhase::kBrute).counters.candidates, n * (n - 1) / 2 + n * m);
  EXPECT_EQ(detect(w, BroadPhase::kBvh).counters.candidates,
            test::face_box_overlaps(w.data, w.vertices()));
  // The fold pushes neighbours of one vertex into each other: those contacts exist, and only
  // the shared-node test finds them.
  EXPECT_GT(sharing_a_node, 0u);
}

TEST(CpuCollision, PackedVec3PositionsGiveBitIdenticalPairsToVec4) {
  CollisionFixture w = three_bodies();
  // The same positions as packed x, y, z (a 12-byte stride), one array per mesh.
  std::vector<std::vector<float>> packed(w.positions.size());
  const auto pack = [&] {
    for (std::size_t m = 0; m < w.positions.size(); ++m) {
      packed[m].resize(3 * w.positions[m].size());
      for (std::size_t i = 0; i < w.positions[m].size(); ++i) {
        for (int c = 0; c < 3; ++c)
          packed[m][3 * i + c] = w.positions[m][i][c];
      }
    }
  };
  pack();
  std::vector<collision::MeshVertices> packed_views;
  std::vector<collision::PositionSource> packed_sources = w.host_sources();
  for (std::size_t m = 0; m < packed.size(); ++m) {
    packed_views.push_back({packed[m].data(), 3u});
    packed_sources[m].host = packed[m].data();
    packed_sources[m].stride_bytes = 3 * sizeof(float);
  }
  // The hierarchies built on either layout are the same.
  collision::CollisionData packed_data = w.data;
  collision::build_hierarchies(packed_data, packed_views.data());
  const auto same_rows = [](const gpu::BoxFace& x, const gpu::BoxFace& y) {
    return x.face == y.face && x.box == y.box;
  };
  const auto same_nodes = [](const gpu::BvhNode& x, const gpu::BvhNode& y) {
    return x.left == y.left && x.right == y.right && x.parent == y.parent && x.face == y.face;
  };
  ASSERT_TRUE(std::equal(packed_data.box_faces.begin(), packed_data.box_faces.end(),
                         w.data.box_faces.begin(), w.data.box_faces.end(), same_rows));
  ASSERT_EQ(packed_data.face_boxes, w.data.face_boxes);
  ASSERT_TRUE(std::equal(packed_data.bvh_nodes.begin(), packed_data.bvh_nodes.end(),
                         w.data.bvh_nodes.begin(), w.data.bvh_nodes.end(), same_nodes));

  const std::unique_ptr<CpuCollision> wide = backend(w);
  CpuCollision narrow;
  narrow.set_positions(packed_sources);
  narrow.upload(packed_data);
  const auto pairs = [](CpuCollision& c, BroadPhase method) {
    c.detect(method);
    std::vector<gpu::FacePair> raw;
    c.download_face_pairs(raw);
    return raw;
  };
  const auto boxes = [](CpuCollision& c) {
    std::vector<gpu::Box> out;
    c.download_boxes(out);
    return out;
  };
  const auto box_bits_equal = [](const std::vector<gpu::Box>& x, const std::vector<gpu::Box>& y) {
    return x.size() == y.size() &&
           std::equal(x.begin(), x.end(), y.begin(), [](const gpu::Box& a, const gpu::Box& b) {
             return glm::vec3(a.min) == glm::vec3(b.min) && glm::vec3(a.max) == glm::vec3(b.max);
           });
  };
  // At rest, then with mesh 1 folded (written in place into both layouts): the bvh pass
  // rebuilds its tree from the positions read through either stride.
  for (int pose = 0; pose < 2; ++pose) {
    if (pose == 1) {
      fold_quarters(w, 1);
      pack();  // same sizes: the arrays stay where they are
    }
    for (BroadPhase method : kMethods) {
      const std::vector<gpu::FacePair> reference = pairs(*wide, method);
      ASSERT_GT(reference.size(), 20u);
      EXPECT_EQ(difference(pairs(narrow, method), reference), "")
          << broadphase_name(method) << ", pose " << pose;
      EXPECT_EQ(narrow.counters().candidates, wide->counters().candidates)
          << broadphase_name(method) << ", pose " << pose;
      if (method == BroadPhase::kOctree) {
        EXPECT_TRUE(box_bits_equal(boxes(narrow), boxes(*wide))) << "pose " << pose;
      }
    }
  }
  EXPECT_EQ(narrow.bvh_trees().rebuild_count(), 1u);
  EXPECT_EQ(wide->bvh_trees().rebuild_count(), 1u);
}

}  // namespace
}  // namespace deformcd::cpu
