// `deformcd view`: runs under a virtual X server (xvfb-run) and draws the scene; without a
// display it says so and points to `deformcd render`.

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "deformcd/render/image.h"
#include "gl/gl_test_context.h"
#include "support/cli_runner.h"

namespace fs = std::filesystem;

namespace deformcd::render {
namespace {

using test::CliRun;
using test::run_cli;

TEST(Viewer, RunsUnderXvfbAndDrawsTheScene) {
  const std::string xvfb_run = DEFORMCD_XVFB_RUN;
  if (xvfb_run.empty()) DEFORMCD_GL_UNAVAILABLE("xvfb-run was not found when configuring");
  const fs::path shot = fs::temp_directory_path() / "deformcd_viewer_test_shot.png";
  fs::remove(shot);
  // Brute force: on llvmpipe it is the faster broad phase for these five frames.
  const CliRun r =
      test::run_shell("cd " + std::string(DEFORMCD_SOURCE_DIR) + " && " +
                      test::kDrawingEnvironment + " " + xvfb_run + " -a " + DEFORMCD_CLI +
                      " view scenes/phase2.json --quit-after 5 --broadphase brute "
                      "--screenshot " +
                      shot.string());
  if (r.status != 0 && r.output.find("OpenGL 4.3") != std::string::npos) {
    DEFORMCD_GL_UNAVAILABLE(r.output);
  }
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("view: frame 5,"), std::string::npos) << r.output;
  // The window showed the bodies: dark edges on the white background.
  const RgbaImage image = read_png(shot);
  int dark = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      dark += image.at(x, y).r < 128 ? 1 : 0;
  EXPECT_GT(dark, 500) << "the screenshot shows no wireframe";
  fs::remove(shot);
}

TEST(Viewer, WithoutADisplayItSaysSoAndPointsToRender) {
  const CliRun r =
      run_cli("view scenes/phase2.json --quit-after 5", "env -u DISPLAY -u WAYLAND_DISPLAY");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("needs a display"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("deformcd render"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace deformcd::render
