// Headless context creation: platform choice, forcing, invalid choices, adoption.

#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <string>
#include <thread>

#include "deformcd/error.h"
#include "deformcd/gl/context.h"
#include "deformcd/gl/device_info.h"
#include "gl/gl_test_context.h"

namespace deformcd::gl {
namespace {

using test_support::ScopedEnv;
using test_support::try_create_context;

constexpr const char* kPlatformVariable = "DEFORMCD_EGL_PLATFORM";

TEST(ParseEglPlatform, AcceptsTheThreeNames) {
  EXPECT_EQ(parse_egl_platform("auto"), EglPlatform::kAuto);
  EXPECT_EQ(parse_egl_platform("device"), EglPlatform::kDevice);
  EXPECT_EQ(parse_egl_platform("surfaceless"), EglPlatform::kSurfaceless);
}

TEST(ParseEglPlatform, RejectsOtherNamesNamingTheOrigin) {
  try {
    (void)parse_egl_platform("Device", "--egl-platform");
    FAIL() << "expected GlError";
  } catch (const GlError& e) {
    EXPECT_STREQ(e.what(), "--egl-platform='Device' is not one of auto, device, surfaceless");
  }
}

TEST(HeadlessContext, InvalidEnvironmentValueIsAClearError) {
  ScopedEnv env(kPlatformVariable, "vulkan");
  try {
    (void)create_headless_context();
    FAIL() << "expected GlError";
  } catch (const GlError& e) {
    EXPECT_STREQ(e.what(),
                 "DEFORMCD_EGL_PLATFORM='vulkan' is not one of auto, device, surfaceless");
  }
}

TEST(HeadlessContext, DefaultIsAHeadlessEglPlatformWithGl43) {
  ScopedEnv env(kPlatformVariable, std::nullopt);
  auto [context, why_not] = try_create_context();
  if (!context) DEFORMCD_GL_UNAVAILABLE(why_not);
  const std::string platform(context->platform_name());
  EXPECT_TRUE(platform == "egl-device" || platform == "egl-surfaceless") << platform;
  EXPECT_NE(context->platform_details().find("EGL 1."), std::string::npos)
      << context->platform_details();
  // Created current: GL answers without make_current().
  EXPECT_GE(epoxy_gl_version(), 43);
}

TEST(HeadlessContext, EnvironmentForcesSurfaceless) {
  ScopedEnv env(kPlatformVariable, "surfaceless");
  auto [context, why_not] = try_create_context();
  if (!context) DEFORMCD_GL_UNAVAILABLE(why_not);
  EXPECT_EQ(context->platform_name(), "egl-surfaceless");
  const DeviceInfo info = query_device_info(*context);
  EXPECT_GE(info.gl_major * 10 + info.gl_minor, 43);
}

TEST(HeadlessContext, EnvironmentForcesDevicePlatformOnly) {
  ScopedEnv env(kPlatformVariable, "device");
  auto [context, why_not] = try_create_context();
  if (context) {
    EXPECT_EQ(context->platform_name(), "egl-device");
    EXPECT_NE(context->platform_details().find("device 0 of"), std::string::npos)
        << context->platform_details();
  } else {
    // Failing is fine (no usable device) as long as nothing else was tried.
    EXPECT_NE(why_not.find("egl-device: "), std::string::npos) << why_not;
    EXPECT_EQ(why_not.find("egl-surfaceless"), std::string::npos) << why_not;
  }
}

TEST(HeadlessContext, OptionsOverrideTheEnvironment) {
  ScopedEnv env(kPlatformVariable, "not-even-valid");
  ContextOptions options;
  options.platform = EglPlatform::kSurfaceless;
  auto [context, why_not] = try_create_context(options);
  if (!context) DEFORMCD_GL_UNAVAILABLE(why_not);
  EXPECT_EQ(context->platform_name(), "egl-surfaceless");
}

TEST(HeadlessContext, TwoContextsOnOneDisplayOutliveEachOther) {
  ContextOptions options;
  options.platform = EglPlatform::kSurfaceless;
  auto first = try_create_context(options);
  if (!first.context) DEFORMCD_GL_UNAVAILABLE(first.why_not);
  {
    auto second = try_create_context(options);
    ASSERT_TRUE(second.context) << second.why_not;
  }
  // Destroying the second must not have terminated the EGL display the first one uses.
  first.context->make_current();
  EXPECT_GE(epoxy_gl_version(), 43);
}

class AdoptedContextTest : public test_support::GlTest {};

TEST_F(AdoptedContextTest, WrapsTheCurrentContextWithoutOwningIt) {
  {
    const std::unique_ptr<Context> adopted = adopt_current_context();
    EXPECT_EQ(adopted->platform_name(), "adopted");
    EXPECT_EQ(adopted->platform_details(), "application's EGL context");
    const DeviceInfo info = query_device_info(*adopted);
    EXPECT_GE(info.gl_major * 10 + info.gl_minor, 43);
  }
  // The wrapper is gone; the context it wrapped is still current and alive.
  EXPECT_NE(glGetString(GL_VERSION), nullptr);
  EXPECT_GE(epoxy_gl_version(), 43);
}

TEST_F(AdoptedContextTest, MakeCurrentCallsTheApplicationsFunction) {
  int calls = 0;
  const std::unique_ptr<Context> adopted = adopt_current_context([&calls] { ++calls; });
  adopted->make_current();
  adopted->make_current();
  EXPECT_EQ(calls, 2);
}

TEST_F(AdoptedContextTest, ThrowsWhenNoContextIsCurrent) {
  // A new thread has no current context.
  std::string message;
  std::thread([&message] {
    try {
      (void)adopt_current_context();
    } catch (const GlError& e) {
      message = e.what();
    }
  }).join();
  EXPECT_EQ(message, "adopt_current_context: no OpenGL context is current on this thread");
}

}  // namespace
}  // namespace deformcd::gl
