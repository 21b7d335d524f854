// Device info: version and the compute limits, checked against the GL 4.3 minimums.

#include <gtest/gtest.h>

#include "deformcd/gl/device_info.h"
#include "gl/gl_test_context.h"

namespace deformcd::gl {
namespace {

class DeviceInfoTest : public test_support::GlTest {};

TEST_F(DeviceInfoTest, ReportsAtLeastGl43) {
  const DeviceInfo info = query_device_info(context());
  EXPECT_GE(info.gl_major * 10 + info.gl_minor, 43);
  EXPECT_FALSE(info.vendor.empty());
  EXPECT_FALSE(info.renderer.empty());
  // GL_VERSION starts with "major.minor".
  EXPECT_EQ(
      info.gl_version.rfind(std::to_string(info.gl_major) + "." + std::to_string(info.gl_minor), 0),
      0u)
      << info.gl_version;
  EXPECT_FALSE(info.glsl_version.empty());
  EXPECT_EQ(info.platform, context().platform_name());
  EXPECT_EQ(info.platform_details, context().platform_details());
}

TEST_F(DeviceInfoTest, ComputeLimitsMeetTheGl43Minimums) {
  // Table 23.75 of the GL 4.3 core specification.
  const DeviceInfo info = query_device_info(context());
  for (int axis = 0; axis < 3; ++axis)
    EXPECT_GE(info.max_work_group_count[axis], 65535u);
  EXPECT_GE(info.max_work_group_size[0], 1024u);
  EXPECT_GE(info.max_work_group_size[1], 1024u);
  EXPECT_GE(info.max_work_group_size[2], 64u);
  EXPECT_GE(info.max_work_group_invocations, 1024u);
  EXPECT_GE(info.max_shared_memory_bytes, 32768u);
  EXPECT_GE(info.max_ssbo_block_bytes, std::uint64_t{1} << 24);
  EXPECT_GE(info.max_ssbo_bindings, 8u);
  EXPECT_GE(info.max_compute_ssbo_blocks, 8u);
}

TEST_F(DeviceInfoTest, DebugBuildsGetADebugContext) {
#ifdef NDEBUG
  EXPECT_FALSE(query_device_info(context()).debug_context);
#else
  EXPECT_TRUE(query_device_info(context()).debug_context);
#endif
}

}  // namespace
}  // namespace deformcd::gl
