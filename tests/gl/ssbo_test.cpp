// Ssbo: upload, download, ranges, moves.

#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include <glm/vec4.hpp>

#include "deformcd/error.h"
#include "deformcd/gl/ssbo.h"
#include "deformcd/gpu_layout.h"
#include "gl/gl_test_context.h"

namespace deformcd::gl {
namespace {

class SsboTest : public test_support::GlTest {};

std::vector<gpu::Spring> some_springs(std::size_t n) {
  std::vector<gpu::Spring> springs(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    springs[i] = {i, i + 1, 0.5f * static_cast<float>(i), 1.0f + static_cast<float>(i)};
  }
  return springs;
}

bool same(const gpu::Spring& x, const gpu::Spring& y) {
  return x.a == y.a && x.b == y.b && x.rest_length == y.rest_length && x.stiffness == y.stiffness;
}

TEST_F(SsboTest, RoundTripsStructs) {
  const std::vector<gpu::Spring> springs = some_springs(1000);
  const Ssbo<gpu::Spring> buffer{std::span<const gpu::Spring>(springs)};
  EXPECT_EQ(buffer.size(), 1000u);
  EXPECT_NE(buffer.name(), 0u);
  const std::vector<gpu::Spring> back = buffer.download();
  ASSERT_EQ(back.size(), springs.size());
  for (std::size_t i = 0; i < springs.size(); ++i)
    EXPECT_TRUE(same(back[i], springs[i])) << i;
}

TEST_F(SsboTest, UploadsAndDownloadsSubranges) {
  std::vector<glm::vec4> zeros(10, glm::vec4(0.0f));
  Ssbo<glm::vec4> buffer{std::span<const glm::vec4>(zeros)};
  const std::vector<glm::vec4> middle = {glm::vec4(1, 2, 3, 4), glm::vec4(5, 6, 7, 8)};
  buffer.upload(middle, 4);
  const std::vector<glm::vec4> all = buffer.download();
  EXPECT_EQ(all[3], glm::vec4(0.0f));
  EXPECT_EQ(all[4], middle[0]);
  EXPECT_EQ(all[5], middle[1]);
  EXPECT_EQ(all[6], glm::vec4(0.0f));
  const std::vector<glm::vec4> part = buffer.download(5, 2);
  ASSERT_EQ(part.size(), 2u);
  EXPECT_EQ(part[0], middle[1]);
  EXPECT_EQ(part[1], glm::vec4(0.0f));
}

TEST_F(SsboTest, RangesPastTheEndThrow) {
  Ssbo<std::uint32_t> buffer(8);
  const std::vector<std::uint32_t> three(3, 7u);
  EXPECT_NO_THROW(buffer.upload(three, 5));
  EXPECT_THROW(buffer.upload(three, 6), GlError);
  EXPECT_THROW((void)buffer.download(7, 2), GlError);
  EXPECT_THROW((void)buffer.download(9, 0), GlError);
  EXPECT_EQ(buffer.download(5, 3), three);
}

TEST_F(SsboTest, MovesTransferTheBuffer) {
  const std::vector<std::uint32_t> values = {1, 2, 3};
  Ssbo<std::uint32_t> a{std::span<const std::uint32_t>(values)};
  const std::uint32_t name = a.name();
  Ssbo<std::uint32_t> b = std::move(a);
  EXPECT_EQ(b.name(), name);
  EXPECT_EQ(b.download(), values);
  EXPECT_EQ(a.name(), 0u);  // NOLINT(bugprone-use-after-move): moved-from state is specified
  EXPECT_EQ(a.size(), 0u);  // NOLINT(bugprone-use-after-move)

  Ssbo<std::uint32_t> c(1);
  c = std::move(b);
  EXPECT_EQ(c.name(), name);
  EXPECT_EQ(c.download(), values);
}

TEST_F(SsboTest, EmptyBufferIsValid) {
  Ssbo<std::uint32_t> empty(0);
  EXPECT_TRUE(empty.download().empty());
  EXPECT_NO_THROW(empty.bind(gpu::kCollisionResult));
}

}  // namespace
}  // namespace deformcd::gl
