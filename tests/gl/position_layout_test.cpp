// Where GlCollision's shaders read each mesh's positions (no GL needed): in place when every
// mesh is in one GL buffer, else gathered region after region with each mesh's stride kept; and
// the sources refused, naming the mesh, before a shader could read a wrong word.

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/collision/collision_backend.h"
#include "deformcd/error.h"
#include "gpu/gl/position_layout.h"

namespace deformcd::gl {
namespace {

using collision::PositionSource;
using Kind = PositionSource::Kind;

const float kSomeFloats[4] = {};

PositionSource gl_source(std::uint32_t buffer, std::uint64_t offset, std::uint64_t stride,
                         std::uint32_t count) {
  return {.kind = Kind::kGl,
          .gl_buffer = buffer,
          .offset_bytes = offset,
          .stride_bytes = stride,
          .vertex_count = count};
}

PositionSource host_source(std::uint64_t stride, std::uint32_t count) {
  return {.kind = Kind::kHost, .host = kSomeFloats, .stride_bytes = stride, .vertex_count = count};
}

const std::vector<std::string> kLabels = {"mesh 0 ('a')", "mesh 1 ('b')", "mesh 2 ('c')"};

TEST(PositionSpanBytes, IsStrideTimesGapsPlusOneVertex) {
  EXPECT_EQ(position_span_bytes(16, 10), 16u * 9 + 12);
  EXPECT_EQ(position_span_bytes(12, 1), 12u);
  EXPECT_EQ(position_span_bytes(12, 0), 0u);
}

TEST(PlanPositionLayout, OneGlBufferIsReadInPlaceAtItsOffsets) {
  const std::vector<PositionSource> sources = {gl_source(7, 0, 16, 10), gl_source(7, 160, 16, 5),
                                               gl_source(7, 1000, 12, 3)};
  const std::vector<std::uint32_t> counts = {10, 5, 3};
  const PositionLayout layout = plan_position_layout(sources, counts, kLabels);
  EXPECT_TRUE(layout.in_place());
  EXPECT_EQ(layout.shared_buffer, 7u);
  EXPECT_EQ(layout.gathered_bytes, 0u);
  ASSERT_EQ(layout.meshes.size(), 3u);
  EXPECT_EQ(layout.meshes[1].word_offset, 40u);
  EXPECT_EQ(layout.meshes[1].word_stride, 4u);
  EXPECT_EQ(layout.meshes[2].word_offset, 250u);
  EXPECT_EQ(layout.meshes[2].word_stride, 3u);
  EXPECT_EQ(layout.meshes[2].span_bytes, 36u);
}

TEST(PlanPositionLayout, OtherwiseEachMeshGetsARegionKeepingItsStride) {
  const std::vector<std::uint32_t> counts = {10, 5, 3};
  for (const std::vector<PositionSource>& sources :
       {std::vector<PositionSource>{gl_source(7, 4, 16, 10), gl_source(8, 0, 20, 5),
                                    gl_source(7, 400, 12, 3)},
        std::vector<PositionSource>{gl_source(7, 4, 16, 10), host_source(20, 5),
                                    gl_source(7, 400, 12, 3)}}) {
    const PositionLayout layout = plan_position_layout(sources, counts, kLabels);
    EXPECT_FALSE(layout.in_place());
    ASSERT_EQ(layout.meshes.size(), 3u);
    // 156, 92 and 36 bytes, one after another.
    EXPECT_EQ(layout.meshes[0].word_offset, 0u);
    EXPECT_EQ(layout.meshes[0].word_stride, 4u);
    EXPECT_EQ(layout.meshes[1].region_offset, 156u);
    EXPECT_EQ(layout.meshes[1].word_offset, 39u);
    EXPECT_EQ(layout.meshes[1].word_stride, 5u);
    EXPECT_EQ(layout.meshes[2].region_offset, 248u);
    EXPECT_EQ(layout.meshes[2].word_stride, 3u);
    EXPECT_EQ(layout.gathered_bytes, 284u);
  }
}

void expect_refused(const std::vector<PositionSource>& sources,
                    const std::vector<std::uint32_t>& counts, const std::string& expected) {
  try {
    (void)plan_position_layout(sources, counts, kLabels);
    ADD_FAILURE() << "expected Error containing: " << expected;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

TEST(PlanPositionLayout, RefusesWhatAShaderWouldMisread) {
  const PositionSource ok = gl_source(7, 0, 16, 10);
  expect_refused({ok}, {10, 5}, "1 position sources for 2 meshes");
  expect_refused({ok, PositionSource{}}, {10, 5}, "mesh 1 ('b')'s positions: none set");
  PositionSource host = host_source(16, 5);
  host.host = nullptr;
  expect_refused({ok, host}, {10, 5}, "mesh 1 ('b')'s positions: a null host array");
  expect_refused({ok, gl_source(0, 0, 16, 5)}, {10, 5}, "GL buffer 0");
  expect_refused({ok, gl_source(7, 6, 16, 5)}, {10, 5}, "an offset of 6 bytes");
  expect_refused({ok, gl_source(7, 0, 18, 5)}, {10, 5}, "a stride of 18 bytes");
  expect_refused({ok, gl_source(7, 0, 8, 5)}, {10, 5}, "a stride of 8 bytes");
  expect_refused({ok, host_source(6, 5)}, {10, 5}, "a stride of 6 bytes");
  // The last word read must be an index below 2^32: offset 2^34 - 16 bytes puts mesh 1's
  // last z at float 2^32 - 4 + 4 x 4 + 2.
  expect_refused({ok, gl_source(7, (std::uint64_t{1} << 34) - 16, 16, 5)}, {10, 5},
                 "beyond the shaders' uint indices");
  expect_refused({ok, gl_source(7, 0, std::uint64_t{1} << 33, 5)}, {10, 5},
                 "beyond the shaders' uint indices");
  // Fits exactly: the last z is float 2^32 - 1.
  EXPECT_NO_THROW((void)plan_position_layout(
      std::vector<PositionSource>{ok, gl_source(7, (std::uint64_t{1} << 34) - 12, 16, 1)},
      std::vector<std::uint32_t>{10, 1}, kLabels));
}

}  // namespace
}  // namespace deformcd::gl
