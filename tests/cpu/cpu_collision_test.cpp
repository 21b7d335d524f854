// The CPU collision backend against the plainest oracle: the narrow phase over every face pair.
// Every broad phase (brute, octree, octree-compact, bvh) must return exactly its pairs.

#include "cpu/cpu_collision.h"

#include <algorithm>
#include <limits>
#include <set>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "core/collision/broad_phase.h"
#include "core/collision/tri_tri_intersection.h"
#include "cpu/cpu_simulation.h"
#include "support/face_box_overlaps.h"
#include "support/world_fixtures.h"

namespace deformcd::cpu {
namespace {

using PairSet = std::set<std::pair<std::uint32_t, std::uint32_t>>;

BodyInit grid_body(int n, double spacing, glm::dvec3 origin) {
  BodyInit init;
  init.body = build_body(test::tet_grid(n, n, n, spacing, origin));
  return init;
}

// Every face of every body pair through tri_tri_intersect: what any broad phase must return.
PairSet all_pairs_oracle(const WorldState& w) {
  PairSet found;
  for (const gpu::BodyPair& bp : w.body_pairs) {
    const gpu::ObjectInfo& a = w.objects[bp.a];
    const gpu::ObjectInfo& b = w.objects[bp.b];
    for (std::uint32_t i = a.face_offset; i < a.face_offset + a.face_count; ++i) {
      for (std::uint32_t j = b.face_offset; j < b.face_offset + b.face_count; ++j) {
        const gpu::Face& fa = w.faces[i];
        const gpu::Face& fb = w.faces[j];
        const glm::vec3 p[3] = {glm::vec3(w.positions[fa.a]), glm::vec3(w.positions[fa.b]),
                                glm::vec3(w.positions[fa.c])};
        const glm::vec3 q[3] = {glm::vec3(w.positions[fb.a]), glm::vec3(w.positions[fb.b]),
                                glm::vec3(w.positions[fb.c])};
        if (collision::tri_tri_intersect(p, q).intersect) found.insert({i, j});
      }
    }
  }
  return found;
}

struct Detected {
  PairSet pairs;
  std::size_t raw_count = 0;  // before removing duplicates: must equal pairs.size()
  std::vector<std::uint32_t> flags;
  gpu::CollisionCounters counters{};
};

Detected detect(const WorldState& w, BroadPhase method, int threads = 0) {
  CpuSimulation sim(threads);
  sim.upload(w);
  CpuCollision collision(sim);
  collision.upload(w);
  collision.detect(method);
  Detected d;
  std::vector<gpu::FacePair> raw;
  collision.download_face_pairs(raw);
  d.raw_count = raw.size();
  for (const gpu::FacePair& p : raw)
    d.pairs.insert({p.face_a, p.face_b});
  collision.download_face_flags(d.flags);
  d.counters = collision.counters();
  return d;
}

PairSet pair_set(const std::vector<gpu::FacePair>& raw) {
  PairSet set;
  for (const gpu::FacePair& p : raw)
    set.insert({p.face_a, p.face_b});
  return set;
}

std::vector<gpu::FacePair> raw_pairs(const WorldState& w, BroadPhase method, int threads) {
  CpuSimulation sim(threads);
  sim.upload(w);
  CpuCollision collision(sim);
  collision.upload(w);
  collision.detect(method);
  std::vector<gpu::FacePair> raw;
  collision.download_face_pairs(raw);
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

// Mirrors the nodes of `body` below its middle height through its middle x plane, then those
// left of it through its middle z plane: quarters turn inside out (their surfaces crossing the
// others'), so the siblings of a tree built on the unfolded shape overlap everywhere.
void fold_quarters(WorldState& w, std::uint32_t body) {
  const gpu::ObjectInfo& o = w.objects[body];
  glm::vec3 lo(std::numeric_limits<float>::max());
  glm::vec3 hi(std::numeric_limits<float>::lowest());
  for (std::uint32_t i = o.node_offset; i < o.node_offset + o.node_count; ++i) {
    lo = glm::min(lo, glm::vec3(w.positions[i]));
    hi = glm::max(hi, glm::vec3(w.positions[i]));
  }
  const glm::vec3 mid = 0.5f * (lo + hi);
  for (std::uint32_t i = o.node_offset; i < o.node_offset + o.node_count; ++i) {
    glm::vec4& p = w.positions[i];
    if (p.y < mid.y) p.x = 2.0f * mid.x - p.x;
    if (p.x < mid.x) p.z = 2.0f * mid.z - p.z;
  }
}

// Three grids: 0 and 1 interpenetrate, 1 and 2 interpenetrate, 0 and 2 are apart. Spacings
// differ so that faces cross at general angles of the grid lines.
WorldState three_bodies() {
  return assemble_world({grid_body(4, 0.25, glm::dvec3(0.0)),
                         grid_body(5, 0.21, glm::dvec3(0.63, 0.31, 0.17)),
                         grid_body(3, 0.3, glm::dvec3(1.41, 0.52, 0.45))});
}

constexpr BroadPhase kMethods[] = {BroadPhase::kBrute, BroadPhase::kOctree,
                                   BroadPhase::kOctreeCompact, BroadPhase::kBvh};

TEST(CpuCollision, EveryMethodReturnsExactlyTheOraclePairs) {
  const WorldState w = three_bodies();
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
    for (std::uint32_t f = 0; f < d.flags.size(); ++f)
      EXPECT_EQ(d.flags[f] != 0u, faces.count(f) == 1) << f;
    EXPECT_EQ(d.counters.colliding_faces, faces.size());
  }
  // Bodies 0 and 2 are apart: no pair between them.
  const std::uint32_t body2_first_face = w.objects[2].face_offset;
  for (const auto& [a, b] : oracle)
    EXPECT_FALSE(a < w.objects[1].face_offset && b >= body2_first_face);
}

TEST(CpuCollision, OctreeCountsOverlappingLeafBoxPairs) {
  const WorldState w = three_bodies();
  const Detected octree = detect(w, BroadPhase::kOctree);
  EXPECT_GT(octree.counters.box_pairs, 0u);
  EXPECT_LT(octree.counters.box_pairs, 3u * 64u * 64u);
  EXPECT_EQ(detect(w, BroadPhase::kOctreeCompact).counters.box_pairs, octree.counters.box_pairs);
  EXPECT_EQ(detect(w, BroadPhase::kBrute).counters.box_pairs, 0u);
  EXPECT_EQ(detect(w, BroadPhase::kBvh).counters.box_pairs, 0u);
}

TEST(CpuCollision, CandidatesCountTheTriangleTestsRun) {
  const WorldState w = three_bodies();
  std::uint64_t all = 0;
  for (const gpu::BodyPair& bp : w.body_pairs)
    all += std::uint64_t{w.objects[bp.a].face_count} * w.objects[bp.b].face_count;
  const Detected brute = detect(w, BroadPhase::kBrute);
  const Detected octree = detect(w, BroadPhase::kOctree);
  const Detected compact = detect(w, BroadPhase::kOctreeCompact);
  const Detected bvh = detect(w, BroadPhase::kBvh);
  EXPECT_EQ(brute.counters.candidates, all);
  // The same first-box-pair rule picks the same tests; only the sweep that finds them differs.
  EXPECT_EQ(compact.counters.candidates, octree.counters.candidates);
  // One face per leaf: the bvh tests exactly the pairs whose own boxes overlap.
  EXPECT_EQ(bvh.counters.candidates, test::face_box_overlaps(w));
  EXPECT_LT(bvh.counters.candidates, octree.counters.candidates);
  EXPECT_LT(octree.counters.candidates, brute.counters.candidates);
  EXPECT_GE(bvh.counters.candidates, bvh.counters.face_pairs);
}

TEST(CpuCollision, BodiesApartHaveNoContactsAndNoBoxPairs) {
  const WorldState w =
      assemble_world({grid_body(3, 0.3, glm::dvec3(0.0)), grid_body(3, 0.3, glm::dvec3(2.0))});
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
  const WorldState w = assemble_world({grid_body(3, 0.3, glm::dvec3(0.0))});
  EXPECT_TRUE(w.body_pairs.empty());
  for (BroadPhase method : kMethods)
    EXPECT_TRUE(detect(w, method).pairs.empty());
}

TEST(CpuCollision, RawPairsAreOneListForEveryThreadCountAndMethod) {
  const WorldState w = three_bodies();
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
  const WorldState rest = three_bodies();
  WorldState folded = rest;
  // Body 1 has the most faces: its tree is the one both of its pairs traverse.
  fold_quarters(folded, 1);
  CpuSimulation sim;
  sim.upload(rest);
  CpuCollision collision(sim);
  collision.upload(rest);
  collision.detect(BroadPhase::kBvh);
  EXPECT_EQ(collision.bvh_trees().rebuild_count(), 0u);

  sim.upload(folded);
  collision.detect(BroadPhase::kBvh);
  const BvhTrees& trees = collision.bvh_trees();
  EXPECT_EQ(trees.rebuild_count(), 1u);
  // Measured on the refitted tree, the fold loosened it past the threshold; the rebuilt tree
  // is the reference from now on.
  EXPECT_EQ(trees.area_ratio(1), trees.built_area_ratio(1));
  std::vector<gpu::FacePair> bvh;
  collision.download_face_pairs(bvh);
  const PairSet oracle = all_pairs_oracle(folded);
  ASSERT_NE(oracle, all_pairs_oracle(rest));
  EXPECT_EQ(pair_set(bvh), oracle);
  collision.detect(BroadPhase::kBrute);
  std::vector<gpu::FacePair> brute;
  collision.download_face_pairs(brute);
  EXPECT_EQ(difference(bvh, brute), "");

  // The same shape again: the fresh tree is as tight as it gets, no second rebuild.
  collision.detect(BroadPhase::kBvh);
  EXPECT_EQ(collision.bvh_trees().rebuild_count(), 1u);
  std::vector<gpu::FacePair> again;
  collision.download_face_pairs(again);
  EXPECT_EQ(difference(again, brute), "");
}

TEST(CpuCollision, BvhLeavesATreeNobodyTraversesAsItIs) {
  const WorldState rest = three_bodies();
  WorldState folded = rest;
  // Body 2 has the fewest faces: its faces query the others' trees, its own tree is only read
  // at the root, which is exact however loose the tree below it.
  fold_quarters(folded, 2);
  CpuSimulation sim;
  sim.upload(folded);
  CpuCollision collision(sim);
  collision.upload(rest);
  collision.detect(BroadPhase::kBvh);
  EXPECT_GT(collision.bvh_trees().area_ratio(2),
            kBvhRebuildFactor * collision.bvh_trees().built_area_ratio(2));
  EXPECT_EQ(collision.bvh_trees().rebuild_count(), 0u);
  std::vector<gpu::FacePair> bvh;
  collision.download_face_pairs(bvh);
  const PairSet oracle = all_pairs_oracle(folded);
  EXPECT_EQ(pair_set(bvh), oracle);
  // The folded body still crosses body 1: its faces did query body 1's tree.
  EXPECT_TRUE(std::any_of(oracle.begin(), oracle.end(), [&](const auto& pair) {
    return pair.second >= folded.objects[2].face_offset;
  }));
}

TEST(CpuCollision, LeafBoxesHoldTheirFacesCurrentVertices) {
  const WorldState w = three_bodies();
  CpuSimulation sim;
  sim.upload(w);
  CpuCollision collision(sim);
  collision.upload(w);
  collision.detect(BroadPhase::kOctree);
  std::vector<gpu::Box> boxes;
  collision.download_boxes(boxes);
  ASSERT_EQ(boxes.size(), 3u * 64u);
  for (const gpu::BoxFace& row : w.box_faces) {
    const gpu::Face& f = w.faces[row.face];
    const gpu::Box& b = boxes[64u * f.body + row.box];
    for (std::uint32_t n : {f.a, f.b, f.c}) {
      const glm::vec3 p(w.positions[n]);
      EXPECT_TRUE(glm::all(glm::lessThanEqual(glm::vec3(b.min), p)));
      EXPECT_TRUE(glm::all(glm::lessThanEqual(p, glm::vec3(b.max))));
    }
  }
}

}  // namespace
}  // namespace deformcd::cpu
