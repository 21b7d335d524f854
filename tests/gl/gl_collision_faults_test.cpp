// The GL backend where the driver refuses memory (gl::fault, src/gpu/gl/fault_injection.h): a
// buffer allocation failing with GL_OUT_OF_MEMORY is a GlError naming the buffer and its size,
// leaves no GL error behind, and a list that cannot grow after an overflow leaves the lists as
// they were, so that the next pass runs and finds every pair.

#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <string>
#include <vector>

#include "deformcd/error.h"
#include "deformcd/gl/ssbo.h"
#include "gl/collision_test_backends.h"
#include "gl/collision_test_worlds.h"
#include "gl/expect_gl_error.h"
#include "gl/gl_test_context.h"
#include "gpu/gl/fault_injection.h"
#include "gpu/gl/gl_collision.h"

namespace deformcd::gl {
namespace {

using fault::Kind;
using fault::ScopedFault;

using test::contains;
using test::gl_error_of;

// The counters need no GL: they only count and say when to fail.
TEST(FaultInjection, ArmedOperationsFailOnlyInTheirWindow) {
  const std::uint64_t before = fault::operations(Kind::kShaderCompile);
  EXPECT_FALSE(fault::should_fail(Kind::kShaderCompile));  // disarmed: counted, never failed
  {
    ScopedFault f(Kind::kShaderCompile, 2, 2);
    EXPECT_FALSE(fault::should_fail(Kind::kShaderCompile));
    EXPECT_TRUE(fault::should_fail(Kind::kShaderCompile));
    EXPECT_TRUE(fault::should_fail(Kind::kShaderCompile));
    EXPECT_FALSE(fault::should_fail(Kind::kShaderCompile));
    EXPECT_FALSE(fault::should_fail(Kind::kMakeCurrent));  // each kind on its own
  }
  {
    ScopedFault forever(Kind::kShaderCompile, 1, fault::kForever);
    EXPECT_TRUE(fault::should_fail(Kind::kShaderCompile));
    EXPECT_TRUE(fault::should_fail(Kind::kShaderCompile));
  }
  EXPECT_FALSE(fault::should_fail(Kind::kShaderCompile));  // disarmed by the scope's end
  EXPECT_EQ(fault::operations(Kind::kShaderCompile), before + 8);
}

class GlCollisionFaultsTest : public test_support::GlTest {};

TEST_F(GlCollisionFaultsTest, ARefusedAllocationIsAGlErrorWithTheSizeAndLeavesNoGlError) {
  std::string message;
  {
    ScopedFault oom(Kind::kBufferAllocation);
    message = gl_error_of([] { Ssbo<glm::vec4> buffer(1000); });
  }
  EXPECT_EQ(message,
            "glBufferData of 16000 bytes failed: GL_OUT_OF_MEMORY (injected by gl::fault)");
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  Ssbo<glm::vec4> next(1000);  // disarmed: allocates
  EXPECT_TRUE(glIsBuffer(next.name()));
}

// Each allocation of an upload in turn is refused: the GlError names that buffer, and the
// previous upload's buffers and results stay readable and usable.
TEST_F(GlCollisionFaultsTest, EveryAllocationOfAnUploadFailsCleanlyAndKeepsThePreviousState) {
  test::GlBackend gl(context(), test::three_crossing_grids());
  const std::vector<gpu::FacePair> expected = gl.expected();
  ASSERT_GT(expected.size(), 10u);
  test::expect_same_pairs(gl.pairs(BroadPhase::kBvh), expected, "before");
  const std::uint64_t before = fault::operations(Kind::kBufferAllocation);
  gl.collision.upload(gl.fixture.data);
  const std::uint64_t per_upload = fault::operations(Kind::kBufferAllocation) - before;
  ASSERT_EQ(per_upload, 20u);  // collision_buffer_sizes lists 20 buffers
  gl.collision.detect(BroadPhase::kBvh);
  const gpu::CollisionCounters counters = gl.collision.counters();
  const std::uint32_t face_pair_buffer = gl.collision.gl_face_pair_buffer();
  for (std::uint64_t n = 1; n <= per_upload; ++n) {
    std::string message;
    {
      ScopedFault oom(Kind::kBufferAllocation, n);
      message = gl_error_of([&] { gl.collision.upload(gl.fixture.data); });
    }
    EXPECT_TRUE(contains(message, "GL collision: allocating ")) << message;
    EXPECT_TRUE(contains(message, "failed: glBufferData of ")) << message;
    EXPECT_TRUE(contains(message, "GL_OUT_OF_MEMORY")) << message;
    if (n == 6) {
      EXPECT_TRUE(contains(message,
                           "allocating Face Pair (SSBO 10), " +
                               std::to_string(48 * gl.collision.face_pair_capacity()) + " bytes (" +
                               std::to_string(gl.collision.face_pair_capacity()) + " x 48)"))
          << message;
    }
    // The last results and buffers as they were.
    EXPECT_EQ(gl.collision.gl_face_pair_buffer(), face_pair_buffer) << n;
    EXPECT_EQ(gl.collision.counters().face_pairs, counters.face_pairs) << n;
    std::vector<gpu::FacePair> pairs;
    gl.collision.download_face_pairs(pairs);
    test::expect_same_pairs(test::sorted(pairs), expected, "after failure " + std::to_string(n));
  }
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  test::expect_same_pairs(gl.pairs(BroadPhase::kBvh), expected, "next pass");
}

// A pass overflows both lists at once (one candidate short, one face-pair slot): growing the
// first (candidates) or the second (face pairs) is refused. Neither list is replaced, the pass's
// results are reported lost (not truncated), and the next pass grows both and finds every pair.
TEST_F(GlCollisionFaultsTest, AListThatCannotGrowKeepsTheListsAndTheNextPassFindsEveryPair) {
  std::uint32_t candidates = 0;
  {
    test::GlBackend gl(context(), test::three_crossing_grids());
    gl.collision.detect(BroadPhase::kBvh);
    candidates = gl.collision.counters().candidates;
  }
  ASSERT_GT(candidates, 10u);
  for (const std::uint64_t n : {1u, 2u}) {
    SCOPED_TRACE("allocation " + std::to_string(n) + " of the growth refused");
    test::GlBackend gl(context(), test::three_crossing_grids(),
                       {.initial_pair_capacity = 1, .initial_candidate_capacity = candidates - 1});
    const std::vector<gpu::FacePair> expected = gl.expected();
    const std::uint32_t pair_buffer = gl.collision.gl_face_pair_buffer();
    gl.collision.detect(BroadPhase::kBvh);
    std::string message;
    {
      ScopedFault oom(Kind::kBufferAllocation, n);
      message = gl_error_of([&] { gl.collision.complete_pass(); });
    }
    const std::string list = n == 1 ? "Candidate Pair (SSBO 28)" : "Face Pair (SSBO 10)";
    const std::string grown = n == 1
                                  ? "growing it from " + std::to_string(candidates - 1) +
                                        " entries after a pass found " + std::to_string(candidates)
                                  : "growing it from 1 entries after a pass found ";
    EXPECT_TRUE(contains(message, "GL collision: allocating " + list)) << message;
    EXPECT_TRUE(contains(message, "GL_OUT_OF_MEMORY")) << message;
    EXPECT_TRUE(contains(message, grown)) << message;
    EXPECT_TRUE(contains(message, "the lists keep their size")) << message;
    // Nothing replaced, the candidates not either when the face pairs failed: the shaders'
    // capacities still match the buffers.
    EXPECT_EQ(gl.collision.candidate_capacity(), candidates - 1);
    EXPECT_EQ(gl.collision.face_pair_capacity(), 1u);
    EXPECT_EQ(gl.collision.gl_face_pair_buffer(), pair_buffer);
    // The reads say the pass was lost, and why, rather than return a truncated list.
    const std::string lost = gl_error_of([&] { (void)gl.collision.counters(); });
    EXPECT_TRUE(
        contains(lost, "the last pass's results are lost (GL collision: allocating " + list))
        << lost;
    EXPECT_TRUE(contains(lost, "the next detect() runs a new pass")) << lost;
    std::vector<gpu::FacePair> pairs;
    EXPECT_THROW(gl.collision.download_face_pairs(pairs), GlError);
    std::vector<std::uint32_t> flags;
    EXPECT_THROW(gl.collision.download_face_flags(flags), GlError);
    // The next pass grows the lists and is whole.
    test::expect_same_pairs(gl.pairs(BroadPhase::kBvh), expected, "next pass");
    EXPECT_GE(gl.collision.face_pair_capacity(), expected.size());
    EXPECT_GE(gl.collision.candidate_capacity(), candidates);
  }
}

// Positions gathered from host arrays into a buffer of ours, allocated by the first pass: when
// the driver refuses it, the pass fails before it runs, and the next one runs normally.
TEST_F(GlCollisionFaultsTest, ARefusedGatheringBufferFailsThePassBeforeItRuns) {
  test::GlBackend gl(context(), test::three_crossing_grids());
  const std::vector<gpu::FacePair> expected = gl.expected();
  std::string message;
  {
    ScopedFault oom(Kind::kBufferAllocation);
    message = gl_error_of([&] { gl.collision.detect(BroadPhase::kBvh); });
  }
  EXPECT_TRUE(contains(message, "GL collision: allocating Gathered Positions (SSBO 0), "))
      << message;
  EXPECT_TRUE(contains(message, "GL_OUT_OF_MEMORY")) << message;
  EXPECT_EQ(gl.collision.counters().face_pairs, 0u);  // no pass ran: the upload's zeros
  test::expect_same_pairs(gl.pairs(BroadPhase::kBvh), expected, "after the failure");
}

}  // namespace
}  // namespace deformcd::gl
