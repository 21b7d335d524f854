#pragma once
// What the GL collision tests share: a GL simulation holding a world's positions with a GL
// collision backend over them, and comparisons of face pairs and flags with host references.

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "collision_test_worlds.h"
#include "deformcd/gl/context.h"
#include "deformcd/gpu_layout.h"
#include "deformcd/world_state.h"
#include "gpu/gl/gl_collision.h"
#include "gpu/gl/gl_simulation.h"

namespace deformcd::test {

/// Same pairs in the same order (both sorted), segments bit for bit.
inline void expect_same_pairs(const std::vector<gpu::FacePair>& actual,
                              const std::vector<gpu::FacePair>& expected, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    const gpu::FacePair& x = actual[i];
    const gpu::FacePair& y = expected[i];
    ASSERT_EQ(x.face_a, y.face_a) << "pair " << i;
    ASSERT_EQ(x.face_b, y.face_b) << "pair " << i;
    EXPECT_EQ(x.coplanar, y.coplanar) << "faces " << x.face_a << ", " << x.face_b;
    EXPECT_EQ(x.segment0, y.segment0) << "faces " << x.face_a << ", " << x.face_b;
    EXPECT_EQ(x.segment1, y.segment1) << "faces " << x.face_a << ", " << x.face_b;
  }
}

/// Flag 1 on every face of `pairs`, 0 elsewhere.
inline std::vector<std::uint32_t> flags_of(const std::vector<gpu::FacePair>& pairs,
                                           std::size_t face_count) {
  std::vector<std::uint32_t> flags(face_count, 0u);
  for (const gpu::FacePair& p : pairs)
    flags[p.face_a] = flags[p.face_b] = 1u;
  return flags;
}

inline std::uint32_t count_set(const std::vector<std::uint32_t>& flags) {
  std::uint32_t n = 0;
  for (std::uint32_t f : flags)
    n += f != 0 ? 1u : 0u;
  return n;
}

/// A simulation holding a world's positions and a collision backend over them.
struct Backends {
  gl::GlSimulation simulation;
  gl::GlCollision collision;

  Backends(gl::Context& context, const WorldState& world,
           const gl::GlCollisionOptions& options = {})
      : simulation(context), collision(context, simulation, options) {
    simulation.upload(world);
    collision.upload(world);
  }

  /// One pass, its face pairs sorted.
  std::vector<gpu::FacePair> pairs(BroadPhase method) {
    collision.detect(method);
    std::vector<gpu::FacePair> out;
    collision.download_face_pairs(out);
    return sorted(out);
  }
};

}  // namespace deformcd::test
