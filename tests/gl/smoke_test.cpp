// A real compute dispatch: every invocation writes i*i + 7 into an SSBO.

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "deformcd/error.h"
#include "deformcd/gl/device_info.h"
#include "deformcd/gl/ssbo.h"
#include "gl/gl_test_context.h"
#include "gpu/gl/compute_program.h"

namespace deformcd::gl {
namespace {

class SmokeTest : public test_support::GlTest {};

constexpr std::uint32_t kSentinel = 0xdeadbeefu;

TEST_F(SmokeTest, EveryInvocationWritesItsValueAndTheGuardKeepsTheTail) {
  ComputeProgram program("test/smoke.comp");
  ASSERT_EQ(program.work_group_size(), (std::array<std::uint32_t, 3>{64, 1, 1}));

  // 3001 is not a multiple of 64: the last group has 57 idle invocations, which would write
  // into the 63-element tail were it not for the shader's bounds check.
  constexpr std::uint32_t kCount = 3001;
  const std::vector<std::uint32_t> initial(kCount + 63, kSentinel);
  const Ssbo<std::uint32_t> values{std::span<const std::uint32_t>(initial)};
  values.bind(0);
  program.set_uniform("u_count", kCount);
  program.dispatch_covering(kCount);

  const std::vector<std::uint32_t> out = values.download();
  for (std::uint32_t i = 0; i < kCount; ++i)
    ASSERT_EQ(out[i], i * i + 7u) << "index " << i;
  for (std::size_t i = kCount; i < out.size(); ++i)
    ASSERT_EQ(out[i], kSentinel) << i;
}

TEST_F(SmokeTest, UnknownUniformIsAnError) {
  ComputeProgram program("test/smoke.comp");
  try {
    program.set_uniform("u_cuont", 1u);
    FAIL() << "expected GlError";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("'test/smoke.comp' has no active uniform 'u_cuont'"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(SmokeTest, DispatchBeyondTheDeviceLimitIsAnError) {
  ComputeProgram program("test/smoke.comp");
  const DeviceInfo info = query_device_info(context());
  if (info.max_work_group_count[1] == UINT32_MAX) GTEST_SKIP() << "no limit to exceed";
  EXPECT_THROW(program.dispatch(1, info.max_work_group_count[1] + 1), GlError);
}

TEST_F(SmokeTest, UnknownShaderNameListsTheEmbeddedOnes) {
  try {
    ComputeProgram program("test/nope.comp");
    FAIL() << "expected GlError";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("no shader named 'test/nope.comp' (embedded: "),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("test/smoke.comp"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace deformcd::gl
