// `deformcd render`: PNG images of chosen frames with the collision colours, and clean
// failures that write nothing.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "deformcd/render/image.h"
#include "gl/gl_test_context.h"
#include "render/pixel_checks.h"
#include "support/cli_runner.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace deformcd::render {
namespace {

using test::CliRun;
using test::run_cli;

class RenderCli : public ::testing::Test {
 protected:
  [[nodiscard]] std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // True when the run failed only because this machine has no GL 4.3 (then the test skips, or
  // fails under DEFORMCD_REQUIRE_GL).
  static bool gl_unavailable(const CliRun& r) {
    return r.status == 1 && r.output.find("needs an OpenGL 4.3 context") != std::string::npos;
  }

  test::TempDir dir_;
};

// Phase 2 (bunny and dragon), the smaller scene: the renderer itself is checked on phase 1 in
// scene_renderer_test.cpp. With 24 frames the bodies overlap the most at frame 12.
TEST_F(RenderCli, WritesTheChosenFramesWithCollisionColoursOnlyInContact) {
  const CliRun r = run_cli("render scenes/phase2.json --frames 24 --at 12,0 --out " +
                           path("images") + " --size 320x240 --broadphase brute");
  if (gl_unavailable(r)) DEFORMCD_GL_UNAVAILABLE(r.output);
  ASSERT_EQ(r.status, 0) << r.output;
  // One line per image, in frame order, with its contact count.
  const std::size_t first = r.output.find("frame_00000.png  frame 0  0 contacts");
  const std::size_t second = r.output.find("frame_00012.png  frame 12  ");
  ASSERT_NE(first, std::string::npos) << r.output;
  ASSERT_NE(second, std::string::npos) << r.output;
  EXPECT_LT(first, second);
  EXPECT_EQ(r.output.find("frame 12  0 contacts"), std::string::npos) << r.output;

  const RgbaImage apart = read_png(path("images/frame_00000.png"));
  const RgbaImage contact = read_png(path("images/frame_00012.png"));
  for (const RgbaImage* image : {&apart, &contact}) {
    EXPECT_EQ(image->width, 320);
    EXPECT_EQ(image->height, 240);
  }
  EXPECT_EQ(test::count_pixels(apart, test::is_red), 0);
  EXPECT_EQ(test::count_pixels(apart, test::is_blue), 0);
  EXPECT_GE(test::count_pixels(contact, test::is_red), 20);
  EXPECT_GE(test::count_pixels(contact, test::is_blue), 20);
  // Exactly the two images, no temporaries.
  EXPECT_EQ(std::distance(fs::directory_iterator(path("images")), fs::directory_iterator()), 2);
}

// On a response scene "0 contacts" would read as if the bodies never met: each image's line
// names the intersecting face pairs and the response's constraints, and a last line says what
// the response did. The overlap scene's bodies start intersecting, so constraints act at once.
TEST_F(RenderCli, OnAResponseSceneSaysWhatTheResponseDid) {
  const CliRun r =
      run_cli("render scenes/overlap.json --at 2 --out " + path("images") + " --size 160x120");
  if (gl_unavailable(r)) DEFORMCD_GL_UNAVAILABLE(r.output);
  ASSERT_EQ(r.status, 0) << r.output;
  const std::size_t line = r.output.find("frame_00002.png  frame 2  ");
  ASSERT_NE(line, std::string::npos) << r.output;
  const std::string image_line = r.output.substr(line, r.output.find('\n', line) - line);
  EXPECT_NE(image_line.find(" intersecting face pair"), std::string::npos) << image_line;
  EXPECT_NE(image_line.find(" contact constraints"), std::string::npos) << image_line;
  EXPECT_EQ(image_line.find(" contacts"), std::string::npos) << image_line;
  EXPECT_NE(r.output.find("response: constraints between bodies in 2 of 2 frames (1-2), at most "),
            std::string::npos)
      << r.output;
}

TEST_F(RenderCli, AFileInTheWayOfOutIsAClearErrorAndNothingIsWritten) {
  std::ofstream(path("taken")) << "keep me";
  const CliRun r = run_cli("render scenes/phase2.json --at 0 --out " + path("taken"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find(path("taken")), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("in the way"), std::string::npos) << r.output;
  std::ifstream in(path("taken"));
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "keep me");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_.path()), fs::directory_iterator()), 1);
}

TEST_F(RenderCli, VideoWithoutFfmpegOnPathFailsClearlyBeforeWritingAnything) {
  fs::create_directories(path("empty_bin"));
  const CliRun r =
      run_cli("render scenes/phase2.json --video " + path("run.mp4") + " --out " + path("frames"),
              "PATH=" + path("empty_bin"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("ffmpeg"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("PATH"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("frames")));
  EXPECT_FALSE(fs::exists(path("run.mp4")));
}

TEST_F(RenderCli, VideoEncodesEveryFrameWithTheFfmpegOnPath) {
  // A stand-in ffmpeg that records its arguments and writes its output file (the last one).
  fs::create_directories(path("bin"));
  std::ofstream(path("bin/ffmpeg")) << "#!/bin/sh\n"
                                       "printf '%s\\n' \"$@\" > \"" +
                                           path("ffmpeg_args.txt") +
                                           "\"\n"
                                           "for last; do :; done\n"
                                           "echo video > \"$last\"\n";
  fs::permissions(path("bin/ffmpeg"), fs::perms::owner_all);
  const CliRun r = run_cli(
      "render scenes/phase2.json --frames 2 --size 64x48 "
      "--broadphase brute --video " +
          path("run.mp4") + " --out " + path("frames"),
      "PATH=" + path("bin") + ":$PATH");
  if (gl_unavailable(r)) DEFORMCD_GL_UNAVAILABLE(r.output);
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* frame : {"frame_00000.png", "frame_00001.png", "frame_00002.png"})
    EXPECT_TRUE(fs::exists(dir_ / "frames" / frame)) << frame;
  EXPECT_TRUE(fs::exists(path("run.mp4")));
  std::ifstream in(path("ffmpeg_args.txt"));
  std::stringstream args;
  args << in.rdbuf();
  EXPECT_NE(args.str().find(path("frames") + "/frame_%05d.png"), std::string::npos) << args.str();
  EXPECT_NE(args.str().find("-framerate\n60\n"), std::string::npos) << args.str();
}

TEST_F(RenderCli, TheCpuBackendIsRejectedWithTheReason) {
  const CliRun r =
      run_cli("render scenes/phase2.json --at 0 --backend cpu --out " + path("images"));
  EXPECT_EQ(r.status, 2) << r.output;  // a usage error
  EXPECT_NE(r.output.find("GL backend"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("images")));
}

TEST_F(RenderCli, FramesOutsideTheRunAreNamed) {
  const CliRun r = run_cli("render scenes/phase2.json --frames 5 --at 2,9 --out " + path("images"));
  EXPECT_EQ(r.status, 2) << r.output;  // a usage error
  EXPECT_NE(r.output.find("frame 9 is outside the run (0 to 5"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("images")));
}

TEST_F(RenderCli, NoFramesChosenIsAnError) {
  const CliRun r = run_cli("render scenes/phase2.json --out " + path("images"));
  EXPECT_EQ(r.status, 2) << r.output;  // a usage error
  EXPECT_NE(r.output.find("--every-frame"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace deformcd::render
