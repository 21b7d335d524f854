// GlSimulation at its boundaries: use before upload, buffers over the limit, inconsistent
// states, and the position buffer it exposes to renderers.

#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <string>
#include <vector>

#include "core/sim/node_force_lists.h"
#include "deformcd/body.h"
#include "deformcd/error.h"
#include "deformcd/simulation_state.h"
#include "gl/gl_test_context.h"
#include "gl/sim_test_worlds.h"
#include "gpu/gl/gl_simulation.h"

namespace deformcd::gl {
namespace {

SimulationState small_world() {
  BodyInit init;
  init.body = build_body(test::tet_grid(2, 2, 2, 0.1));
  return assemble_simulation({init});
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

class GlSimulationErrorsTest : public test_support::GlTest {};

TEST_F(GlSimulationErrorsTest, UseBeforeUploadIsAnError) {
  GlSimulation gl(context());
  std::vector<glm::vec4> out;
  EXPECT_THROW(gl.substep(test::substep_constants(1e-3f)), Error);
  EXPECT_THROW(gl.download_positions(out), Error);
  EXPECT_THROW(gl.download_velocities(out), Error);
  EXPECT_EQ(gl.node_buffers().gl_positions, 0u);
}

// upload() compares every buffer with the limit before allocating: the spring edges (16 bytes
// each) and their states exceed it here while the per-node buffers fit. The failed upload
// keeps the previous state, which goes on stepping.
TEST_F(GlSimulationErrorsTest, BuffersOverTheLimitAreNamedAndThePreviousStateKept) {
  const SimulationState small = small_world();
  BodyInit big_body;
  big_body.body = build_body(test::tet_grid(4, 4, 4, 0.1));
  const SimulationState big = assemble_simulation({big_body});
  const std::size_t big_edges = sim::build_spring_edges(big).size();
  const std::uint64_t limit = 16 * big_edges - 1;
  ASSERT_LT(16 * (big.node_count() + 1), limit);
  ASSERT_GE(limit, 16 * small.springs.size());

  GlSimulation gl(context(), {.max_buffer_bytes = limit});
  gl.upload(small);
  const sim::SubstepConstants c = test::substep_constants(1e-3f, {0.0f, -9.81f, 0.0f});
  gl.substep(c);
  std::vector<glm::vec4> before, after;
  gl.download_positions(before);
  try {
    gl.upload(big);
    FAIL() << "expected GlError";
  } catch (const GlError& e) {
    const std::string what = e.what();
    const std::string edges = std::to_string(big_edges);
    const std::string bytes = std::to_string(16 * big_edges);
    EXPECT_TRUE(contains(what, "Spring Edge (SSBO 2): " + bytes + " bytes (" + edges + " x 16)"))
        << what;
    EXPECT_TRUE(contains(what, "Edge State (SSBO 14): " + bytes)) << what;
    EXPECT_TRUE(contains(
        what, "GlSimulationOptions::max_buffer_bytes (" + std::to_string(limit) + " bytes)"))
        << what;
    EXPECT_FALSE(contains(what, "Node Position")) << what;
  }
  gl.download_positions(after);
  EXPECT_EQ(after, before);
  gl.substep(c);
  gl.download_positions(after);
  EXPECT_EQ(after.size(), small.node_count());
  EXPECT_NE(after, before);
}

TEST_F(GlSimulationErrorsTest, AnInconsistentStateIsRejected) {
  SimulationState world = small_world();
  world.springs[3].b = static_cast<std::uint32_t>(world.node_count());
  GlSimulation gl(context());
  try {
    gl.upload(world);
    FAIL() << "expected Error";
  } catch (const Error& e) {
    EXPECT_TRUE(contains(e.what(), "spring 3 joins nodes")) << e.what();
  }
}

// The buffer a renderer would draw from holds the node positions.
TEST_F(GlSimulationErrorsTest, PositionBufferHoldsThePositions) {
  const SimulationState world = small_world();
  GlSimulation gl(context());
  gl.upload(world);
  gl.substep(test::substep_constants(1e-3f, {0.0f, -9.81f, 0.0f}));
  const std::uint32_t name = gl.node_buffers().gl_positions;
  ASSERT_NE(name, 0u);
  ASSERT_TRUE(glIsBuffer(name));

  std::vector<glm::vec4> expected, read(world.node_count());
  gl.download_positions(expected);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, name);
  glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0,
                     static_cast<GLsizeiptr>(read.size() * sizeof(glm::vec4)), read.data());
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(read, expected);
  EXPECT_NE(read, world.positions);
}

}  // namespace
}  // namespace deformcd::gl
