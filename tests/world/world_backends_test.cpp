// The same world on the GL and the CPU backend: positions agree bit for bit after 200 frames of
// every shipped scene. The shaders do the CPU's float operations in its order, products and sums
// `precise` (no fused multiply-add), and llvmpipe rounds division and square root correctly as
// the CPU does; a GPU whose division is off by an ulp would agree to rounding only.

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <ostream>
#include <string>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "deformcd/world.h"
#include "support/sanitizers.h"
#include "support/world_fixtures.h"

namespace fs = std::filesystem;

namespace deformcd {
namespace {

class BackendAgreement : public ::testing::TestWithParam<const char*> {};

TEST_P(BackendAgreement, GlMatchesCpuAfter200Frames) {
  constexpr int kFrames = 200;
  const Scene scene =
      read_scene(fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / (std::string(GetParam()) + ".json"));
  // The paths span the scene's own length; 200 frames cover part of it.
  const std::vector<BodyInit> bodies = make_scene_bodies(scene, read_tetgen, scene.settings.frames);

  // The simulation alone: collision detection is compared on equal positions elsewhere
  // (tests/gl/collision_agreement_test.cpp).
  WorldOptions gl_options;
  gl_options.backend = BackendKind::kGl;
  gl_options.broadphase = BroadPhase::kNone;
  std::unique_ptr<World> gl_world;
  try {
    gl_world = std::make_unique<World>(bodies, step_settings(scene.settings), gl_options);
  } catch (const GlError& e) {
    if (std::getenv("DEFORMCD_REQUIRE_GL")) FAIL() << e.what();
    GTEST_SKIP() << "no GL 4.3 context: " << e.what();
  }
  WorldOptions cpu_options;
  cpu_options.backend = BackendKind::kCpu;
  cpu_options.broadphase = BroadPhase::kNone;
  World cpu_world(bodies, step_settings(scene.settings), cpu_options);
  for (int f = 0; f < kFrames; ++f) {
    gl_world->step();
    cpu_world.step();
  }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Bounds box = compute_bounds(bodies[b].body);
    const double size = glm::length(box.max - box.min);
    const std::vector<glm::vec3> g = gl_world->positions(b), c = cpu_world.positions(b);
    ASSERT_EQ(g.size(), c.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < g.size(); ++i) {
      worst = std::max(worst, static_cast<double>(glm::length(g[i] - c[i])));
    }
    EXPECT_EQ(worst, 0.0) << GetParam() << " body " << b << ": " << worst << " m apart ("
                          << worst / size << " of its size)";
    RecordProperty(std::string("max_distance_body") + std::to_string(b), std::to_string(worst));
  }
}

INSTANTIATE_TEST_SUITE_P(ShippedScenes, BackendAgreement,
                         ::testing::Values("hanging", "phase1", "phase2"));

// With contact response the detector's exact pass feeds the untangling and the proximity search
// the projections: the whole response pipeline on both backends, bit for bit. The overlap
// scene's bodies start intersecting and come apart; the folding plate's flaps meet with
// self-contact; the impact's bodies meet, flatten and rebound. The impact is chaotic (a 1e-7
// shear of its start moves the CPU's result by 0.06-0.15 of the body size, docs/benchmarks.md),
// so only equal bits can agree on it. Every run takes the response's defaults (self-contact,
// the volume floor, motion-bounded substeps) except the lean impact, which turns those three
// off to run through the whole contact (frames 15-70) between the bodies: with them on, a frame
// in contact takes about 10 s on llvmpipe, so their impact run stops after the first contact.
struct ResponseRun {
  const char* name;  ///< the test's name
  const char* scene;
  int frames;
  bool lean;  ///< self-contact, volume_floor and substep_motion off
};

void PrintTo(const ResponseRun& run, std::ostream* out) {
  *out << run.scene << ", " << run.frames << " frames" << (run.lean ? ", lean" : "");
}

class ResponseBackendAgreement : public ::testing::TestWithParam<ResponseRun> {};

TEST_P(ResponseBackendAgreement, GlEqualsCpu) {
  const ResponseRun run = GetParam();
  Scene scene =
      read_scene(fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / (std::string(run.scene) + ".json"));
  ASSERT_TRUE(scene.response.has_value());
  if (run.lean) {
    scene.collision.self = false;
    scene.response->volume_floor = 0.0f;
    scene.response->substep_motion = 0.0f;
  }
  const std::vector<BodyInit> bodies = make_scene_bodies(scene, read_tetgen, scene.settings.frames);
  WorldOptions options;
  options.response = scene.response;
  options.self_collision = scene.collision.self;
  options.backend = BackendKind::kGl;
  std::unique_ptr<World> gl_world;
  try {
    gl_world = std::make_unique<World>(bodies, step_settings(scene.settings), options);
  } catch (const GlError& e) {
    if (std::getenv("DEFORMCD_REQUIRE_GL")) FAIL() << e.what();
    GTEST_SKIP() << "no GL 4.3 context: " << e.what();
  }
  options.backend = BackendKind::kCpu;
  World cpu_world(bodies, step_settings(scene.settings), options);
  for (int f = 0; f < run.frames; ++f) {
    gl_world->step();
    cpu_world.step();
    ASSERT_EQ(gl_world->contacts().size(), cpu_world.contacts().size()) << "frame " << f + 1;
  }
  EXPECT_TRUE(gl_world->contacts().empty());
  EXPECT_TRUE(cpu_world.contacts().empty());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Bounds box = compute_bounds(bodies[b].body);
    const double size = glm::length(box.max - box.min);
    const std::vector<glm::vec3> g = gl_world->positions(b), c = cpu_world.positions(b);
    double worst = 0.0;
    for (std::size_t i = 0; i < g.size(); ++i)
      worst = std::max(worst, static_cast<double>(glm::length(g[i] - c[i])));
    EXPECT_EQ(worst, 0.0) << "body " << b << ": " << worst << " m apart (" << worst / size
                          << " of its size)";
    RecordProperty(std::string("max_distance_body") + std::to_string(b), std::to_string(worst));
  }
}

// Under AddressSanitizer (about 20x slower on the CPU side) the impact is left out: what it adds
// here is agreement, not host memory paths the other two scenes do not take.
constexpr ResponseRun kResponseRuns[] = {
    {"overlap", "overlap", 40, false},
    {"fold_response", "fold_response", 120, false},  // the flaps meet from frame 10
#ifndef DEFORMCD_UNDER_ASAN
    {"impact", "impact", 24, false},
    {"impact_lean", "impact", 80, true},
#endif
};

INSTANTIATE_TEST_SUITE_P(ResponseScenes, ResponseBackendAgreement,
                         ::testing::ValuesIn(kResponseRuns),
                         [](const ::testing::TestParamInfo<ResponseRun>& param) {
                           return std::string(param.param.name);
                         });

// Sleeping (ResponseSettings::sleep) on both backends: a resting block falls asleep, a block
// dropped onto it wakes it, and the two fall asleep together (tests/world/body_sleep_test.cpp
// asserts that story on the CPU). Each frame the backends agree on who sleeps, and at the end on
// every position, bit for bit: the GL backend holds a sleeping body's nodes through the same
// inverse masses, read back and written in place.
TEST(SleepBackendAgreement, GlEqualsCpuAsBlocksSleepAndWake) {
  constexpr int kFrames = 240;
  const std::vector<BodyInit> bodies = test::blocks_over_a_slab(3.0);
  std::unique_ptr<World> gl_world;
  try {
    gl_world =
        std::make_unique<World>(bodies, test::sleep_step(), test::sleep_options(BackendKind::kGl));
  } catch (const GlError& e) {
    if (std::getenv("DEFORMCD_REQUIRE_GL")) FAIL() << e.what();
    GTEST_SKIP() << "no GL 4.3 context: " << e.what();
  }
  World cpu_world(bodies, test::sleep_step(), test::sleep_options(BackendKind::kCpu));
  int changes = 0;
  bool lower_was_asleep = false;
  for (int f = 1; f <= kFrames; ++f) {
    gl_world->step();
    cpu_world.step();
    for (std::size_t b = 0; b < bodies.size(); ++b)
      ASSERT_EQ(gl_world->asleep(b), cpu_world.asleep(b)) << "body " << b << ", frame " << f;
    changes += cpu_world.asleep(1) != lower_was_asleep ? 1 : 0;
    lower_was_asleep = cpu_world.asleep(1);
  }
  EXPECT_GE(changes, 3) << "the lower block should sleep, wake and sleep again";
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const std::vector<glm::vec3> g = gl_world->positions(b), c = cpu_world.positions(b);
    ASSERT_EQ(g.size(), c.size());
    EXPECT_EQ(std::memcmp(g.data(), c.data(), g.size() * sizeof(glm::vec3)), 0) << "body " << b;
  }
}

}  // namespace
}  // namespace deformcd
