// The README's detector example, compiled and run as printed there; the test also checks that
// the README still prints exactly this code.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

// README detector example begins
#include <deformcd/detector.h>

#include <cstdio>
#include <vector>

// A caller's own meshes: a square cloth of two triangles (open) and a tetrahedron's surface,
// positions in the caller's arrays, moved in place from frame to frame.
int readme_detector_example() {
  std::vector<glm::vec3> cloth = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
  std::vector<glm::vec3> tet = {
      {0, 0.5f, 0}, {0.5f, 1.5f, 0}, {-0.5f, 1.5f, 0.3f}, {0, 1.5f, -0.5f}};
  deformcd::Detector detector(
      {{.vertex_count = 4, .triangles = {{0, 1, 2}, {0, 2, 3}}, .name = "cloth"},
       {.vertex_count = 4, .triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}}},
      {.backend = deformcd::BackendKind::kCpu, .broadphase = deformcd::BroadPhase::kBvh});
  detector.set_positions(0, std::span<const glm::vec3>(cloth));  // read in place
  detector.set_positions(1, std::span<const glm::vec3>(tet));
  int total = 0;
  for (int frame = 0; frame < 10; ++frame) {
    for (glm::vec3& p : tet)
      p.y -= 0.1f;  // the caller moves its mesh; no refit to call
    detector.detect();
    for (const deformcd::Contact& c : detector.contacts()) {
      std::printf("frame %d: mesh %u triangle %u x mesh %u triangle %u\n", frame, c.a.body,
                  c.a.face, c.b.body, c.b.face);
      ++total;
    }
  }
  return total;
}
// README detector example ends

namespace {

std::string between(const std::string& text, const std::string& begin, const std::string& end) {
  const std::size_t b = text.find(begin);
  const std::size_t e = text.find(end, b);
  if (b == std::string::npos || e == std::string::npos) return {};
  const std::size_t start = text.find('\n', b) + 1;
  return text.substr(start, text.rfind('\n', e) + 1 - start);
}

TEST(ReadmeDetectorExample, FindsTheTetrahedronThroughTheClothInTheFramesItCrosses) {
  // The tip starts 0.5 above the cloth and the base 1.5: it crosses from frame 4 to frame 14.
  EXPECT_GT(readme_detector_example(), 6);
}

TEST(ReadmeDetectorExample, IsTheCodeTheReadmePrints) {
  std::ifstream in(DEFORMCD_SOURCE_DIR "/README.md");
  std::stringstream readme;
  readme << in.rdbuf();
  std::ifstream self(DEFORMCD_SOURCE_DIR "/tests/collision/readme_detector_example_test.cpp");
  std::stringstream source;
  source << self.rdbuf();
  const std::string code =
      between(source.str(), "// README detector example begins", "// README detector example ends");
  ASSERT_FALSE(code.empty());
  EXPECT_NE(readme.str().find(code), std::string::npos)
      << "README.md does not print this example as it is here";
}

}  // namespace
