// The CPU collision backend against the plainest oracle: the narrow phase over every face pair.

#include "cpu/cpu_collision.h"

#include <algorithm>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "core/collision/tri_tri_intersection.h"
#include "cpu/cpu_simulation.h"
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

// Three grids: 0 and 1 interpenetrate, 1 and 2 interpenetrate, 0 and 2 are apart. Spacings
// differ so that faces cross at general angles of the grid lines.
WorldState three_bodies() {
  return assemble_world({grid_body(4, 0.25, glm::dvec3(0.0)),
                         grid_body(5, 0.21, glm::dvec3(0.63, 0.31, 0.17)),
                         grid_body(3, 0.3, glm::dvec3(1.41, 0.52, 0.45))});
}

TEST(CpuCollision, BruteAndOctreeReturnExactlyTheOraclePairs) {
  const WorldState w = three_bodies();
  const PairSet oracle = all_pairs_oracle(w);
  ASSERT_GT(oracle.size(), 20u);
  for (BroadPhase method : {BroadPhase::kBrute, BroadPhase::kOctree}) {
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
  EXPECT_EQ(detect(w, BroadPhase::kBrute).counters.box_pairs, 0u);
}

TEST(CpuCollision, BodiesApartHaveNoContactsAndNoBoxPairs) {
  const WorldState w =
      assemble_world({grid_body(3, 0.3, glm::dvec3(0.0)), grid_body(3, 0.3, glm::dvec3(2.0))});
  for (BroadPhase method : {BroadPhase::kBrute, BroadPhase::kOctree}) {
    const Detected d = detect(w, method);
    EXPECT_TRUE(d.pairs.empty());
    EXPECT_EQ(d.counters.box_pairs, 0u);
    EXPECT_EQ(std::count(d.flags.begin(), d.flags.end(), 0u), static_cast<long>(d.flags.size()));
  }
}

TEST(CpuCollision, OneBodyHasNoPairsToTest) {
  const WorldState w = assemble_world({grid_body(3, 0.3, glm::dvec3(0.0))});
  EXPECT_TRUE(w.body_pairs.empty());
  EXPECT_TRUE(detect(w, BroadPhase::kOctree).pairs.empty());
}

TEST(CpuCollision, ResultsDoNotDependOnTheThreadCount) {
  const WorldState w = three_bodies();
  CpuSimulation one(1);
  one.upload(w);
  CpuCollision c1(one);
  c1.upload(w);
  c1.detect(BroadPhase::kOctree);
  std::vector<gpu::FacePair> serial;
  c1.download_face_pairs(serial);
  const Detected parallel = detect(w, BroadPhase::kOctree, 2);
  PairSet serial_set;
  for (const gpu::FacePair& p : serial)
    serial_set.insert({p.face_a, p.face_b});
  EXPECT_EQ(serial_set, parallel.pairs);
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
