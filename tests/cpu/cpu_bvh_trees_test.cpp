// The CPU BVH refit, cut into subtrees refitted in parallel: the same boxes and area ratios as
// the serial collision::refit_bvh and collision::bvh_area_ratio, bit for bit, on any number of
// threads.

#include "cpu/cpu_bvh_trees.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "core/collision/bvh.h"
#include "cpu/executor.h"
#include "support/collision_fixtures.h"
#include "support/world_fixtures.h"

namespace deformcd::cpu {
namespace {

// A big mesh (4,800 faces: its tree is cut into a dozen subtrees) and a small one (one subtree).
test::CollisionFixture big_and_small() {
  BodyInit a;
  a.body = build_body(test::tet_grid(20, 20, 20, 0.05, glm::dvec3(0.0)));
  BodyInit b;
  b.body = build_body(test::tet_grid(3, 3, 3, 0.3, glm::dvec3(0.5, 0.3, 0.2)));
  return test::collision_fixture({a, b});
}

// Moves every vertex in place (the views still point at the arrays), differently with `phase`.
void wobble(test::CollisionFixture& f, float phase) {
  for (std::vector<glm::vec4>& mesh : f.positions) {
    for (glm::vec4& v : mesh) {
      const glm::vec3 p(v);
      v = glm::vec4(p + 0.02f * glm::vec3(std::sin(7.0f * p.y + phase), std::cos(5.0f * p.z),
                                          std::sin(3.0f * p.x - phase)),
                    v.w);
    }
  }
}

bool same_bits(const std::vector<gpu::Box>& x, const std::vector<gpu::Box>& y) {
  return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(gpu::Box)) == 0;
}

bool same_bits(double x, double y) {
  return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y);
}

TEST(BvhTrees, TheBigTreeIsCutIntoManySubtrees) {
  const test::CollisionFixture f = big_and_small();
  const gpu::BodyBvh& t = f.data.mesh_bvhs[0];
  const collision::BvhCut cut = collision::cut_bvh(f.data.bvh_nodes, t.root, t.node_count);
  EXPECT_GE(cut.subtrees.size(), 8u);
}

TEST(BvhTrees, ParallelRefitGivesTheSerialBoxesAndRatiosOnEveryThreadCount) {
  test::CollisionFixture f = big_and_small();
  const collision::CollisionData& d = f.data;
  // One BvhTrees per thread count, all uploaded on the rest pose.
  const std::vector<int> thread_counts = {1, 2, 3, 4};
  std::vector<std::unique_ptr<Executor>> executors;
  std::vector<BvhTrees> trees(thread_counts.size());
  for (std::size_t k = 0; k < thread_counts.size(); ++k) {
    executors.push_back(std::make_unique<Executor>(thread_counts[k]));
    executors[k]->run([&] { trees[k].upload(d, f.vertices()); });
  }
  for (int frame = 0; frame < 8; ++frame) {
    wobble(f, 0.3f * static_cast<float>(frame));
    std::vector<gpu::Box> serial(d.bvh_nodes.size());
    std::vector<double> ratios;
    for (const gpu::BodyBvh& t : d.mesh_bvhs) {
      collision::refit_bvh(d.bvh_nodes, t.root, t.node_count, f.vertices(), d.faces, serial);
      ratios.push_back(collision::bvh_area_ratio(d.bvh_nodes, t.root, t.node_count, serial));
    }
    for (std::size_t k = 0; k < thread_counts.size(); ++k) {
      executors[k]->run([&] { trees[k].refit(f.vertices()); });
      EXPECT_TRUE(same_bits(trees[k].boxes(), serial))
          << thread_counts[k] << " threads, frame " << frame;
      for (std::uint32_t m = 0; m < ratios.size(); ++m) {
        EXPECT_TRUE(same_bits(trees[k].area_ratio(m), ratios[m]))
            << "mesh " << m << ", " << thread_counts[k] << " threads, frame " << frame << ": "
            << trees[k].area_ratio(m) << " against " << ratios[m];
      }
    }
  }
}

}  // namespace
}  // namespace deformcd::cpu
