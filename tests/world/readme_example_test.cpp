// The README's library example, compiled and run as it is printed there (keep them in step).

#include <gtest/gtest.h>

// README example begins
#include <deformcd/scene.h>
#include <deformcd/tetrahedralize.h>
#include <deformcd/world.h>

#include <cstdio>

int readme_example(const char* scene_file) {
  deformcd::Scene scene = deformcd::read_scene(scene_file);
  deformcd::WorldOptions options;
  options.backend = deformcd::BackendKind::kCpu;  // or kGl, or kAuto (GL when available)
  deformcd::World world(deformcd::make_scene_bodies(scene, deformcd::load_model, 60),
                        deformcd::step_settings(scene.settings), options);
  for (int frame = 0; frame < 60; ++frame)
    world.step();
  for (std::size_t b = 0; b < world.body_count(); ++b) {
    const std::vector<glm::vec3> p = world.positions(b);
    std::printf("%s: %zu nodes, node 0 at (%g, %g, %g)\n", world.body_name(b).c_str(), p.size(),
                p[0].x, p[0].y, p[0].z);
  }
  return 0;
}
// README example ends

TEST(ReadmeExample, RunsOnTheShippedPhase2Scene) {
  EXPECT_EQ(readme_example(DEFORMCD_SOURCE_DIR "/scenes/phase2.json"), 0);
}
