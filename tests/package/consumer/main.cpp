// Two tetrahedra's surfaces crossing each other, detected through the installed package.
#include <deformcd/detector.h>

#include <cstdio>
#include <vector>

int main() {
  const std::vector<deformcd::Triangle> tet = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  std::vector<glm::vec3> a = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  std::vector<glm::vec3> b = {
      {0.2f, 0.2f, 0.2f}, {1.2f, 0.2f, 0.2f}, {0.2f, 1.2f, 0.2f}, {0.2f, 0.2f, 1.2f}};
  deformcd::Detector detector(
      {{.vertex_count = 4, .triangles = tet}, {.vertex_count = 4, .triangles = tet}},
      {.backend = deformcd::BackendKind::kCpu});
  detector.set_positions(0, std::span<const glm::vec3>(a));
  detector.set_positions(1, std::span<const glm::vec3>(b));
  detector.detect();
  const std::size_t contacts = detector.contacts().size();
  std::printf("%zu contacts\n", contacts);
  return contacts > 0 ? 0 : 1;
}
