// Coulomb friction (issue 33, item 3): a block at rest on a fixed incline of 28 degrees, steeper
// than its dynamic friction angle (24.2) and below its static one (35.0), stays put. The incline
// is a fixed level slab under gravity tilted by 28 degrees (the same physics, the slide along x).
// Before the stick / slide switch compared the slip with the substep's accumulated normal change,
// it compared it with each projection's own (only the first projection's was not about zero),
// and the block slid 0.86 m in 2 s, as with the dynamic coefficient alone: the issue's "static
// friction has no effect".
//
// Not asserted, since they fail today (docs/notes/2026-12-03-contact-metric.md): just below the
// static angle (static 0.55 or 0.6 at 28 degrees) the block slides about 0.9 m (the static bound
// is met constraint by constraint, and the elastic block's shear when the load comes on breaks
// some); above it, the slide is a third short of Coulomb's 0.5 (g sin a - mu_d g cos a) t^2.

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/vec3.hpp>

#include "deformcd/world.h"
#include "deformcd/world_intersections.h"
#include "support/world_fixtures.h"

namespace deformcd {
namespace {

constexpr float kStatic = 0.7f;    // the static angle: atan 0.7 = 35.0 degrees
constexpr float kDynamic = 0.45f;  // the dynamic angle: 24.2 degrees
constexpr float kGravity = 9.81f;
constexpr int kFrames = 120;  // 2 s at 60 frames a second  // 2 s at 60 frames a second

// A fixed slab 2 m long (x) with its top at y = 0, and a 10 cm block of stiff material resting
// on it, its bottom at the contact thickness (2 mm), near the slab's upper end.
std::vector<BodyInit> block_on_slab() {
  std::vector<BodyInit> bodies(2);
  bodies[0].name = "incline";
  bodies[0].body = build_body(test::tet_grid(40, 1, 6, 0.05, {-1.0, -0.05, -0.15}));
  for (std::uint32_t i = 0; i < bodies[0].body.positions.size(); ++i)
    bodies[0].fixed.push_back(i);
  BodyOptions stiff;
  stiff.stiffness = 1.0e5;
  bodies[1].name = "block";
  bodies[1].body = build_body(test::tet_grid(2, 2, 2, 0.05, {-0.8877, 0.002, -0.0323}), stiff);
  bodies[1].damping = 0.0002f;
  bodies[1].volume_stiffness = 1.0e5f;
  return bodies;
}

// The mean x of the block's lowest layer of nodes (the face on the slab): where it slides,
// without the shear of the elastic block under the load along the incline.
double base_x(const World& world, std::size_t body) {
  double sum = 0.0;
  int count = 0;
  const std::vector<glm::vec3> p = world.positions(body);
  for (const glm::vec3& x : p) {
    if (x.y < 0.01f) {
      sum += x.x;
      ++count;
    }
  }
  return sum / count;
}

struct Slide {
  double distance = 0.0;  // m, the block's centroid along the incline after 2 s
  std::uint64_t intersecting_frames = 0;
};

ResponseSettings incline_response() {
  ResponseSettings response;
  response.thickness = 0.002f;
  response.friction_static = kStatic;
  response.friction_dynamic = kDynamic;
  return response;
}

// The block at rest: dropped onto the level slab (gravity straight down) from the thickness and
// settled for 1 s under heavy velocity damping. A mass-spring block placed with its springs at
// rest is not at rest on a surface: it sags and bounces, lifts off and lands with a slip that
// breaks static friction, after which nothing but the dynamic coefficient holds it.
std::vector<BodyInit> settled_block_on_slab() {
  std::vector<BodyInit> bodies = block_on_slab();
  StepSettings step;
  step.dt = 1.0f / 60.0f;
  step.substeps = 10;
  step.velocity_damping = 20.0f;
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  options.response = incline_response();
  World world(bodies, step, options);
  for (int f = 0; f < 60; ++f)
    world.step();
  const std::vector<glm::vec3> settled = world.positions(1);
  for (std::size_t i = 0; i < settled.size(); ++i)
    bodies[1].body.positions[i] = glm::vec4(settled[i], bodies[1].body.positions[i].w);
  return bodies;
}

// The settled block on an incline of `degrees` (the slab level, gravity tilted), for 2 s on the
// CPU with `threads` threads, without damping of the whole.
Slide slide_on_incline(double degrees, int threads = 0) {
  const double a = degrees * std::numbers::pi / 180.0;
  StepSettings step;
  step.dt = 1.0f / 60.0f;
  step.substeps = 10;
  step.gravity =
      kGravity * glm::vec3(static_cast<float>(std::sin(a)), -static_cast<float>(std::cos(a)), 0.0f);
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  options.cpu_threads = threads;
  options.response = incline_response();
  World world(settled_block_on_slab(), step, options);
  WorldIntersections census(world);
  const double start = base_x(world, 1);
  Slide slide;
  for (int f = 0; f < kFrames; ++f) {
    world.step();
    if (census.count().any()) ++slide.intersecting_frames;
  }
  slide.distance = base_x(world, 1) - start;
  return slide;
}

TEST(FrictionIncline, StaticFrictionHoldsABlockTheDynamicAloneWouldNot) {
  const Slide slide = slide_on_incline(28.0);  // tan 28 = 0.53: above 0.45, below 0.7
  EXPECT_LT(std::abs(slide.distance), 0.01) << "slid " << slide.distance << " m in 2 s";
  EXPECT_EQ(slide.intersecting_frames, 0u);
  RecordProperty("distance_m", std::to_string(slide.distance));
}

}  // namespace
}  // namespace deformcd
