// Every shipped scene (scenes/*.json) passes its own checks: built and stepped a few frames on
// the CPU as `deformcd run` steps it (its broad phase, self-collision and response), the world
// has nothing to warn about (World::notice(): a substep longer than the estimated stable one;
// on the CPU backend nothing else) and the frames run without a blow-up. A user's first runs
// are of these scenes: a warning there reads as a fault of the tool.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "deformcd/world.h"
#include "support/shipped_scenes.h"

namespace fs = std::filesystem;

namespace deformcd {
namespace {

class ShippedScene : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedScene, RunsAFewFramesWithoutAWarning) {
  constexpr int kFrames = 3;
  const fs::path file = fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / (GetParam() + ".json");
  const Scene scene = read_scene(file);
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  options.broadphase = parse_broadphase(scene.collision.broadphase);
  options.self_collision = scene.collision.self;
  options.response = scene.response;
  // The shipped scenes use TetGen models (read_tetgen; a surface model would need TetGen).
  World world(make_scene_bodies(scene, read_tetgen, scene.settings.frames),
              step_settings(scene.settings), options);
  EXPECT_EQ(world.notice(), "") << file.string() << " (substep "
                                << scene.settings.dt / scene.settings.substeps
                                << " s, estimated stable up to " << world.estimated_max_substep()
                                << " s)";
  for (int f = 0; f < kFrames; ++f)
    ASSERT_NO_THROW(world.step()) << file.string() << ", frame " << f + 1;
}

INSTANTIATE_TEST_SUITE_P(Scenes, ShippedScene, ::testing::ValuesIn(test::shipped_scene_names()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

// The advice "substeps >= N" (a world's notice and its blow-up messages) is a bound the run keeps:
// the paper's phase 1 with its springs 10 x stiffer, or 10 x more damped, runs at the advised
// count. Before the estimate counted the springs' damping (stiffness-proportional, taken from the
// old velocity, so it shortens the stable substep), both were advised fewer substeps (39 and 13)
// and blew up in the first frame at them.
TEST(ShippedScenes, RunAtTheAdvisedSubstepsWhenMadeStifferOrMoreDamped) {
  const fs::path file = fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / "phase1.json";
  for (const bool stiffer : {true, false}) {
    Scene scene = read_scene(file);
    for (BodySpec& body : scene.bodies) {
      if (stiffer) {
        body.material.stiffness *= 10.0;
      } else {
        body.material.damping *= 10.0;
      }
    }
    const auto build = [&] {
      WorldOptions options;
      options.backend = BackendKind::kCpu;
      options.broadphase = BroadPhase::kNone;
      return std::make_unique<World>(make_scene_bodies(scene, read_tetgen, scene.settings.frames),
                                     step_settings(scene.settings), options);
    };
    scene.settings.substeps = 1;
    // The advice World's notice and blow-up messages give: ceil(dt / the stable substep).
    scene.settings.substeps =
        static_cast<int>(std::ceil(scene.settings.dt / build()->estimated_max_substep()));
    const std::unique_ptr<World> built = build();
    World& world = *built;
    EXPECT_EQ(world.notice(), "") << (stiffer ? "stiffer" : "more damped");
    for (int f = 0; f < 10; ++f)
      ASSERT_NO_THROW(world.step()) << (stiffer ? "stiffer" : "more damped") << ", "
                                    << scene.settings.substeps << " substeps, frame " << f + 1;
  }
}

TEST(ShippedScenes, AreThere) {  // a wrong folder would make the suite above empty
  EXPECT_GE(test::shipped_scene_names().size(), 8u);
}

}  // namespace
}  // namespace deformcd
