// What the user is told when no 4.3 context can be had. Mesa lets us provoke that: with
// MESA_GL_VERSION_OVERRIDE=4.2 it offers no 4.3 core context. The driver reads the variable once
// per process, so the attempt runs in gl_context_probe.

#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <sys/wait.h>
#include <array>
#include <cstdio>
#include <string>

#include "gl/gl_test_context.h"

namespace deformcd::gl {
namespace {

struct ProbeResult {
  int exit_code = -1;
  std::string output;
};

ProbeResult run_probe() {
  ProbeResult result;
  FILE* pipe = ::popen(DEFORMCD_CONTEXT_PROBE, "r");
  if (pipe == nullptr) return result;
  std::array<char, 512> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr) {
    result.output += buffer.data();
  }
  const int status = ::pclose(pipe);
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  return result;
}

class ContextFailureTest : public test_support::GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    const std::string version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    if (version.find("Mesa") == std::string::npos) {
      GTEST_SKIP() << "MESA_GL_VERSION_OVERRIDE needs Mesa; the driver is " << version;
    }
  }
};

TEST_F(ContextFailureTest, ProbeSucceedsWithoutOverride) {
  test_support::ScopedEnv override_version("MESA_GL_VERSION_OVERRIDE", std::nullopt);
  test_support::ScopedEnv platform("DEFORMCD_EGL_PLATFORM", std::nullopt);
  const ProbeResult probe = run_probe();
  EXPECT_EQ(probe.exit_code, 0) << probe.output;
  EXPECT_NE(probe.output.find("platform=egl-"), std::string::npos) << probe.output;
}

TEST_F(ContextFailureTest, NoGl43NamesWhatWasFoundAndTheCpuBackend) {
  test_support::ScopedEnv override_version("MESA_GL_VERSION_OVERRIDE", "4.2");
  test_support::ScopedEnv platform("DEFORMCD_EGL_PLATFORM", std::nullopt);
  const ProbeResult probe = run_probe();
  EXPECT_EQ(probe.exit_code, 1) << probe.output;
  const std::string& m = probe.output;
  EXPECT_NE(m.find("no OpenGL 4.3 core context could be created"), std::string::npos) << m;
  EXPECT_NE(m.find("--backend cpu"), std::string::npos) << m;
  // Every platform, with the EGL implementation found and the GL version it offers instead.
  EXPECT_NE(m.find("\n  egl-device: "), std::string::npos) << m;
  EXPECT_NE(m.find("\n  egl-surfaceless: EGL 1."), std::string::npos) << m;
  EXPECT_NE(m.find("no core context 4.6..4.3 (eglCreateContext: EGL_BAD_"), std::string::npos) << m;
  EXPECT_NE(m.find("the best this platform offers is GL 4.2"), std::string::npos) << m;
}

TEST_F(ContextFailureTest, ForcedPlatformFailureSaysItWasForced) {
  test_support::ScopedEnv override_version("MESA_GL_VERSION_OVERRIDE", "4.2");
  test_support::ScopedEnv platform("DEFORMCD_EGL_PLATFORM", "surfaceless");
  const ProbeResult probe = run_probe();
  EXPECT_EQ(probe.exit_code, 1) << probe.output;
  EXPECT_NE(probe.output.find("Platforms tried (forced by DEFORMCD_EGL_PLATFORM=surfaceless):"),
            std::string::npos)
      << probe.output;
  EXPECT_EQ(probe.output.find("egl-device"), std::string::npos) << probe.output;
}

}  // namespace
}  // namespace deformcd::gl
