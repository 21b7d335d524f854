// The CPU contact response on hand-placed nodes: what its projections do to them (the GL
// backend's agreement with it is tests/gl/gl_contact_response_test.cpp's).

#include <cstdint>
#include <memory>

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

}  // namespace
}  // namespace deformcd
