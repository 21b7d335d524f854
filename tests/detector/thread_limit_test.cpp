// Issue 34, item 2: one thread limit (kMaxThreads) for every entry point, refused with an
// InputError naming the option, never clamped or left to oneTBB (which crashes at ten million).

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "deformcd/detector.h"
#include "deformcd/error.h"
#include "deformcd/limits.h"
#include "deformcd/world.h"
#include "detector/detector_scenes.h"
#include "support/world_fixtures.h"

namespace deformcd {
namespace {

std::string detector_error(int threads) {
  std::vector<CollisionMesh> meshes{test::sphere_mesh(1, 1.0f, {}).mesh};
  try {
    Detector detector(std::move(meshes), {.backend = BackendKind::kCpu, .threads = threads});
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

std::string world_error(int threads) {
  try {
    World world(test::blocks_over_a_slab(0.1), test::sleep_step(),
                test::sleep_options(BackendKind::kCpu, threads));
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

TEST(ThreadLimit, TheLimitItselfIsAccepted) {
  EXPECT_EQ(kMaxThreads, 256);
  EXPECT_EQ(detector_error(kMaxThreads), "");
  EXPECT_EQ(detector_error(0), "");
}

TEST(ThreadLimit, DetectorRefusesCountsPastTheLimitAndNegativeOnes) {
  const std::string expected =
      "threads: must be 0 (every core) or 1 to 256 (deformcd::kMaxThreads)";
  for (int threads : {kMaxThreads + 1, 10'000'000, 2'147'483'647, -1}) {
    const std::string message = detector_error(threads);
    EXPECT_EQ(message, expected + ", got " + std::to_string(threads)) << threads;
  }
}

TEST(ThreadLimit, WorldRefusesThemWithTheSameMessage) {
  EXPECT_EQ(world_error(kMaxThreads + 1),
            "threads: must be 0 (every core) or 1 to 256 (deformcd::kMaxThreads), got 257");
  EXPECT_EQ(world_error(-5),
            "threads: must be 0 (every core) or 1 to 256 (deformcd::kMaxThreads), got -5");
}

}  // namespace
}  // namespace deformcd
