// The CPU contact response on hand-placed nodes: what its projections do to them (the GL
// backend's agreement with it is tests/gl/gl_contact_response_test.cpp's).

#include <cstdint>
#include <memory>
#include <random>

#include <gtest/gtest.h>

#include "core/response/contact_constraints.h"
#include "core/response/frame_constraints.h"
#include "cpu/cpu_contact_response.h"
#include "gl/contact_test_worlds.h"

namespace deformcd {
namespace {

constexpr float kThickness = 0.01f;

gpu::ContactPair constraint(std::uint32_t kind, glm::uvec4 nodes) {
  gpu::ContactPair p{};
  for (int k = 0; k < 4; ++k)
    p.nodes[k] = nodes[k];
  p.kind = kind;
  p.side = kind == gpu::kContactVertexFace ? 1.0f : 0.0f;
  p.thickness = kThickness;
  return p;
}

// An edge from a light node L (inverse mass 100) to a heavy one H (1) falls at 1 m/s onto a
// fixed floor (z = 0), both 0.009 m above it (within the 0.01 m thickness): the edge crosses
// over a fixed edge of the floor a quarter of the way from L (an edge-edge constraint), and H
// lies over a fixed face (a vertex-face constraint). The edge-edge constraint alone stops its
// contact point as a rigid lever would, throwing L up at about a third of the approach while H
// goes on down; once H's own constraint stops H, the lever's push on L is too much, and the
// projection must take it back: both nodes end at rest on the floor, neither thrown off it nor
// still falling.
TEST(CpuContactResponse, ALightNodeIsNotThrownOffWhereItsEdgesHeavyEndIsStopped) {
  const std::vector<glm::vec4> x = {
      {0.0f, 0.02f, 0.009f, 100.0f},  // 0: L
      {0.0f, -0.06f, 0.009f, 1.0f},   // 1: H
      {-0.1f, 0.0f, 0.0f, 0.0f},      // 2, 3: the floor's edge under the edge L H
      {0.1f, 0.0f, 0.0f, 0.0f},       //
      {-0.1f, -0.12f, 0.0f, 0.0f},    // 4, 5, 6: the floor's face under H (normal +z)
      {0.1f, -0.12f, 0.0f, 0.0f},     //
      {0.0f, 0.0f, 0.0f, 0.0f},       //
  };
  std::vector<glm::vec4> v(x.size(), glm::vec4(0.0f));
  v[0].z = v[1].z = -1.0f;
  SimulationState state = test::free_nodes(x, v, std::vector<std::uint32_t>(x.size(), 0u), 1);
  response::FrameConstraints c;
  c.pairs = {constraint(gpu::kContactEdgeEdge, {0, 1, 2, 3}),
             constraint(gpu::kContactVertexFace, {1, 4, 5, 6})};
  for (gpu::ContactPair& p : c.pairs) {
    p.gap = -INFINITY;  // awake
  }
  c.node_motion.assign(x.size(), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));  // no stray

  cpu::CpuContactResponse response(state, std::make_shared<cpu::Executor>(1));
  response.begin_frame(c);
  response::ContactConstants k{};
  k.h = 1.0f / 960.0f;
  k.elapsed = k.h;
  EXPECT_FALSE(response.project(k, 8));
  EXPECT_NEAR(state.velocities[0].z, 0.0f, 0.02f) << "L: thrown off, or still falling";
  EXPECT_NEAR(state.velocities[1].z, 0.0f, 0.02f) << "H";
  // Moved back by the approach cancelled (1 m/s x h, about 1 mm), to the thickness or above.
  EXPECT_GT(state.positions[0].z, 0.009f);
  EXPECT_GT(state.positions[1].z, 0.009f);
}

// contact_clear, the activity pass's bound before the geometry, never clears a constraint that
// acts (contact_geometry's C < 0), and clears most of those beyond their thickness: random edge
// pairs and vertex-face pairs at 0.3-3 thicknesses (their relative placements drawn at random,
// some nearly parallel or degenerate), near the origin and 1 km from it.
TEST(ContactConstraints, ClearNeverHidesAnActingConstraint) {
  std::mt19937 random(12345);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const auto direction = [&] {
    glm::vec3 d(unit(random), unit(random), unit(random));
    return glm::length(d) > 1e-3f ? glm::normalize(d) : glm::vec3(1.0f, 0.0f, 0.0f);
  };
  int acting = 0, beyond = 0, cleared = 0;
  for (int i = 0; i < 200000; ++i) {
    const std::uint32_t kind = i % 2 == 0 ? gpu::kContactEdgeEdge : gpu::kContactVertexFace;
    const glm::vec3 origin = i % 4 < 2 ? glm::vec3(0.0f) : glm::vec3(1000.0f, -700.0f, 300.0f);
    const float edge = 0.05f;  // 5 thicknesses
    const float gap = kThickness * (0.3f + 2.7f * 0.5f * (unit(random) + 1.0f));
    glm::vec3 x[4];
    if (kind == gpu::kContactEdgeEdge) {
      // Edge a through the origin, edge b through a point `gap` away along their common normal
      // (then moved along itself, so the segments need not cross).
      const glm::vec3 da = direction();
      glm::vec3 db = direction();
      if (i % 10 == 0) db = glm::normalize(da + 1e-3f * direction());  // nearly parallel
      glm::vec3 n = glm::cross(da, db);
      n = glm::length(n) > 1e-6f ? glm::normalize(n) : glm::vec3(0.0f, 0.0f, 1.0f);
      const float sa = 0.5f * (unit(random) + 1.0f), sb = 0.5f * (unit(random) + 1.0f);
      const glm::vec3 shift = 0.2f * edge * unit(random) * db;
      x[0] = origin - sa * edge * da;
      x[1] = x[0] + edge * da;
      x[2] = origin + gap * n - sb * edge * db + shift;
      x[3] = x[2] + edge * db;
    } else {
      // A face around the origin, the vertex `gap` in front of (or beside) it.
      const glm::vec3 n = direction();
      const glm::vec3 t = glm::normalize(glm::cross(n, direction() + glm::vec3(0.0f, 0.0f, 2.0f)));
      const glm::vec3 b = glm::cross(n, t);
      x[1] = origin + edge * (-0.5f * t - 0.3f * b);
      x[2] = origin + edge * (0.6f * t - 0.2f * b);
      x[3] = origin + edge * (0.1f * t + 0.7f * b);
      if (i % 10 == 1) x[3] = x[2] + 1e-4f * edge * t;  // a sliver
      x[0] = origin + gap * n + 0.4f * edge * (unit(random) * t + unit(random) * b);
    }
    gpu::ContactPair pair = constraint(kind, glm::uvec4(0u, 1u, 2u, 3u));
    glm::vec3 normal(0.0f);
    float weights[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float c = 0.0f;
    const bool acts = response::contact_geometry(pair, x, normal, weights, c) && c < 0.0f;
    const bool clear = response::contact_clear(pair, x);
    ASSERT_FALSE(acts && clear) << "constraint " << i << " (kind " << kind << ", gap " << gap
                                << ") acts (C = " << c << ") but was cleared";
    acting += acts ? 1 : 0;
    if (gap > 1.05f * kThickness) {
      ++beyond;
      cleared += clear ? 1 : 0;
    }
  }
  EXPECT_GT(acting, 10000);  // the test reaches constraints that act
  // The bound is loose only for nearly parallel edges and vertices beside their face.
  EXPECT_GT(cleared, beyond / 2) << cleared << " of " << beyond;
}

}  // namespace
}  // namespace deformcd
