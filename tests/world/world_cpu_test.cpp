// Worlds on the CPU backend: shipped scenes behave, blow-ups are caught.

#include <filesystem>

#include <gtest/gtest.h>

#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "deformcd/world.h"
#include "support/world_fixtures.h"

namespace fs = std::filesystem;

namespace deformcd {
namespace {

fs::path scene_path(const char* name) {
  return fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / (std::string(name) + ".json");
}

// Steps `world` up to `frames` frames and returns the message of the SimulationError that must
// stop it (a failure, and "", when none does); `site` receives the error's site.
std::string blow_up_message(World& world, int frames, BlowUpSite* site = nullptr) {
  try {
    for (int f = 0; f < frames; ++f)
      world.step();
  } catch (const SimulationError& e) {
    if (site != nullptr) *site = e.site();
    return e.what();
  }
  ADD_FAILURE() << "expected SimulationError within " << frames << " frames";
  return "";
}

double kinetic_energy(const World& world, const std::vector<BodyInit>& bodies) {
  double e = 0.0;
  for (std::size_t b = 0; b < world.body_count(); ++b) {
    const std::vector<glm::vec3> v = world.velocities(b);
    for (std::size_t i = 0; i < v.size(); ++i) {
      e += 0.5 * bodies[b].body.node_mass[i] * glm::dot(glm::dvec3(v[i]), glm::dvec3(v[i]));
    }
  }
  return e;
}

TEST(WorldCpu, HangingBodySagsAndComesToRest) {
  const Scene scene = read_scene(scene_path("hanging"));
  const int frames = scene.settings.frames;
  const std::vector<BodyInit> bodies = make_scene_bodies(scene, read_tetgen, frames);
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  World world(bodies, step_settings(scene.settings), options);
  const float top_before = [&] {
    float lowest = 1e9f;
    for (const glm::vec3& p : world.positions(0))
      lowest = std::min(lowest, p.y);
    return lowest;
  }();
  double peak = 0.0;
  for (int f = 0; f < frames; ++f) {
    world.step();
    if (f % 5 == 0) peak = std::max(peak, kinetic_energy(world, bodies));
  }
  const double final_energy = kinetic_energy(world, bodies);
  EXPECT_GT(peak, 0.0);
  EXPECT_LT(final_energy, 1e-6 * peak) << "peak " << peak << ", final " << final_energy;
  float lowest_after = 1e9f;
  for (const glm::vec3& p : world.positions(0))
    lowest_after = std::min(lowest_after, p.y);
  EXPECT_LT(lowest_after, top_before - 0.05f) << "the body should sag under gravity";
}

TEST(WorldCpu, BlowUpStopsWithTheBodyFrameAndAdvice) {
  BodyInit init;
  init.name = "jelly";
  BodyOptions options;
  options.stiffness = 1.0e9;  // far too stiff for the step below
  init.body = build_body(test::tet_grid(3, 3, 3, 0.1), options);
  init.body.positions[5].y += 0.03f;
  StepSettings settings;
  settings.dt = 0.05f;
  WorldOptions world_options;
  world_options.backend = BackendKind::kCpu;
  world_options.stability_check_interval = 1;
  World world({init}, settings, world_options);
  const std::string msg = blow_up_message(world, 50);
  EXPECT_NE(msg.find("'jelly'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("by frame"), std::string::npos) << msg;
  EXPECT_NE(msg.find("smaller dt or more substeps"), std::string::npos) << msg;
}

// With contact response, a blow-up inside a frame (the positions turn to inf or NaN between
// substeps, before the world's own check at the frame's end) stops with the world's report,
// naming the body and the frame, not with the detector's complaint about the reaches it was
// handed.
TEST(WorldCpu, BlowUpUnderContactResponseStopsWithTheBodyAndAdvice) {
  std::vector<BodyInit> bodies(2);
  for (int b = 0; b < 2; ++b) {
    bodies[b].name = b == 0 ? "jelly" : "block";
    BodyOptions options;
    options.stiffness = b == 0 ? 1.0e15 : 1.0e4;  // the jelly far too stiff for the step below
    bodies[b].body = build_body(test::tet_grid(3, 3, 3, 0.1), options);
    for (glm::vec4& x : bodies[b].body.positions)
      x.y += b == 0 ? 0.0f : 0.302f;  // the block rests just above the jelly
  }
  bodies[0].body.positions[5].y += 0.03f;
  StepSettings settings;
  settings.dt = 0.05f;
  settings.substeps = 8;
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  options.stability_check_interval = 1000;  // the response meets the blow-up first
  options.response = ResponseSettings{};
  World world(bodies, settings, options);
  const std::string msg = blow_up_message(world, 50);
  // The world's own report (its frame and suggested substeps), saying where it was met.
  EXPECT_NE(msg.find("became unstable"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'jelly') by frame 1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("found by the contact response's check of what the integration gave it"),
            std::string::npos)
      << msg;
  EXPECT_EQ(msg.find("in the contact response"), std::string::npos) << msg;
  EXPECT_NE(msg.find("substeps >= "), std::string::npos) << msg;
}

// Issue 34, item 7: a blow-up with nothing in contact (the bodies 0.83 m apart) is the
// integration's, which the response's check only found: the message must not blame the
// contact response.
TEST(WorldCpu, ABlowUpWithNothingInContactIsNotBlamedOnTheContactResponse) {
  std::vector<BodyInit> bodies(2);
  for (int b = 0; b < 2; ++b) {
    bodies[b].name = b == 0 ? "jelly" : "block";
    BodyOptions options;
    options.stiffness = b == 0 ? 1.0e15 : 1.0e4;
    bodies[b].body = build_body(test::tet_grid(3, 3, 3, 0.1), options);
    for (glm::vec4& x : bodies[b].body.positions)
      x.y += b == 0 ? 0.0f : 1.13f;  // 0.83 m above the jelly's top
  }
  bodies[0].body.positions[5].y += 0.03f;
  StepSettings settings;
  settings.dt = 0.05f;
  settings.substeps = 8;
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  options.stability_check_interval = 1000;
  options.response = ResponseSettings{};
  World world(bodies, settings, options);
  BlowUpSite site;
  const std::string msg = blow_up_message(world, 50, &site);
  EXPECT_NE(msg.find("'jelly') by frame 1"), std::string::npos) << msg;
  EXPECT_EQ(msg.find("in the contact response"), std::string::npos) << msg;
  EXPECT_NE(msg.find("what the integration gave it"), std::string::npos) << msg;
  // The same as fields: the response's check found it, in frame 1, on the jelly.
  EXPECT_EQ(site.stage, "response");
  EXPECT_EQ(site.frame, 1);
  EXPECT_EQ(site.body, 0);
  EXPECT_EQ(site.body_name, "jelly");
  EXPECT_GE(site.node, 0);
  EXPECT_NE(msg.find("node " + std::to_string(site.node)), std::string::npos) << msg;
}

TEST(WorldCpu, RejectsABodyWithoutSurfaceFaces) {
  BodyInit init;
  init.name = "hollow";
  init.body = build_body(test::tet_grid(1, 1, 1, 0.1));
  init.body.faces.clear();
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  try {
    World world({init}, StepSettings{}, options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("hollow: body has no surface faces"), std::string::npos)
        << e.what();
  }
}

TEST(WorldCpu, OneBodySceneRuns) {
  BodyOptions soft;
  soft.stiffness = 1.0e3;
  BodyInit init;
  init.body = build_body(test::tet_grid(2, 2, 2, 0.1), soft);
  StepSettings settings;
  settings.substeps = 10;
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  World world({init}, settings, options);
  for (int f = 0; f < 10; ++f)
    world.step();
  EXPECT_EQ(world.frame(), 10);
  EXPECT_EQ(world.body_count(), 1u);
}

TEST(WorldCpu, RejectsUnknownBackendNamesListingTheValidOnes) {
  try {
    (void)parse_backend("cuda");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("valid: auto, gl, cpu"), std::string::npos);
  }
}

}  // namespace
}  // namespace deformcd
