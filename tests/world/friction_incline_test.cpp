// Coulomb friction (issue 33, item 3): a 10 cm elastic block settled on a fixed level slab, then
// gravity tilted by the incline's angle (the same physics as a tilted slab, the slide along x).
// Below its static angle the block stays put; above it, its lowest nodes slide as Coulomb says,
// 0.5 (g sin a - mu_d g cos a) t^2, within 10 %.
//
// Before the friction total was a vector clamped to its cone at every iteration (it was the sum
// of each iteration's magnitude, and a constraint slid as soon as its own cone overflowed), the
// block slid about 0.9 m in 2 s on 28 degrees with static 0.6 (static angle 31.0), and slid a
// third short of Coulomb's distance above it (docs/notes/2026-12-04-friction.md).
//
// Sticking and sliding are a state kept across substeps (response::solve_contact): a block
// tilted at once rings, the net friction the step load asks of the slab rises to about 0.78 x the
// normal load within 0.1 s, and with static 0.6 or 0.55 / dynamic 0.45 on 28 degrees it breaks
// loose and, once sliding, dynamic 0.45 (below tan 28 = 0.53) never stops it; with static 0.7 it
// holds. Tilted gradually (World::set_gravity every frame) there is no step load: static 0.55
// (static angle 28.8) holds, and just past the static angle the block slides within 10 % of
// Coulomb's distance integrated over the tilt (docs/notes/2026-12-05-friction-tilt.md).

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/vec3.hpp>

#include "deformcd/error.h"
#include "deformcd/world.h"
#include "deformcd/world_intersections.h"
#include "support/world_fixtures.h"

namespace deformcd {
namespace {

constexpr float kGravity = 9.81f;
constexpr float kFramesPerSecond = 60.0f;

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

ResponseSettings incline_response(float friction_static, float friction_dynamic) {
  ResponseSettings response;
  response.thickness = 0.002f;
  response.friction_static = friction_static;
  response.friction_dynamic = friction_dynamic;
  return response;
}

// The block (body 1) of `bodies` settled: 1 s of `step` under heavy velocity damping (20 /s),
// its positions then taken as the body's start.
void settle(std::vector<BodyInit>& bodies, StepSettings step, const WorldOptions& options) {
  step.velocity_damping = 20.0f;
  World world(bodies, step, options);
  for (int f = 0; f < 60; ++f)
    world.step();
  const std::vector<glm::vec3> settled = world.positions(1);
  for (std::size_t i = 0; i < settled.size(); ++i)
    bodies[1].body.positions[i] = glm::vec4(settled[i], bodies[1].body.positions[i].w);
}

// The block at rest: dropped onto the level slab (gravity straight down) from the thickness and
// settled (static 0.7, dynamic 0.45). A mass-spring block placed with its springs at rest is not
// at rest on a surface: it sags and bounces, lifts off and lands with a slip that breaks static
// friction.
std::vector<BodyInit> settled_block_on_slab() {
  std::vector<BodyInit> bodies = block_on_slab();
  StepSettings step;
  step.dt = 1.0f / kFramesPerSecond;
  step.substeps = 10;
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  options.response = incline_response(0.7f, 0.45f);
  settle(bodies, step, options);
  return bodies;
}

struct Incline {
  double degrees = 28.0;
  float friction_static = 0.7f;
  float friction_dynamic = 0.45f;
  int frames = 120;  // 2 s
  /// Settled on the incline itself first (gravity tilted, 1 s under heavy velocity damping),
  /// then released: no step load when the run starts.
  bool gentle = false;
  /// Frames over which the incline tilts from level to `degrees` (World::set_gravity every
  /// frame, the angle growing linearly), the first of the run's `frames`; 0: tilted at once.
  int ramp_frames = 0;
};

struct Slide {
  double distance = 0.0;  // m, the lowest nodes' mean x from the tilt to the end
  double coulomb = 0.0;   // m, coulomb_distance: 0 where static friction holds
  std::uint64_t intersecting_frames = 0;
};

// Gravity tilted by `radians` towards +x.
glm::vec3 tilted_gravity(double radians) {
  return kGravity * glm::vec3(static_cast<float>(std::sin(radians)),
                              -static_cast<float>(std::cos(radians)), 0.0f);
}

// The incline's angle (radians) during frame f (0-based) of the run: ramped over ramp_frames.
double incline_angle(const Incline& incline, int f) {
  const double full = incline.degrees * std::numbers::pi / 180.0;
  if (f >= incline.ramp_frames) return full;
  return full * (f + 1) / static_cast<double>(incline.ramp_frames);
}

// Coulomb's slide of a rigid block over the run, the angle held over each frame as the world
// holds it: at rest while tan a <= mu_s, then g (sin a - mu_d cos a) along the slope (never
// back up), integrated in 1,000 steps a frame.
double coulomb_distance(const Incline& incline) {
  constexpr int kSteps = 1000;
  const double h = 1.0 / (kFramesPerSecond * kSteps);
  double x = 0.0, v = 0.0;
  bool sliding = false;
  for (int f = 0; f < incline.frames; ++f) {
    const double a = incline_angle(incline, f);
    if (!sliding && std::tan(a) > incline.friction_static) sliding = true;
    if (!sliding) continue;
    const double along = kGravity * (std::sin(a) - incline.friction_dynamic * std::cos(a));
    for (int k = 0; k < kSteps; ++k) {
      v = std::max(0.0, v + along * h);
      x += v * h;
    }
  }
  return x;
}

// The settled block on the incline (the slab level, gravity tilted at the first frame or over
// the ramp; with `gentle`, settled under the tilt first), on the CPU, without damping of the
// whole.
Slide slide_on_incline(const Incline& incline) {
  StepSettings step;
  step.dt = 1.0f / kFramesPerSecond;
  step.substeps = 10;
  step.gravity = tilted_gravity(incline_angle(incline, 0));
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  options.response = incline_response(incline.friction_static, incline.friction_dynamic);
  std::vector<BodyInit> bodies = settled_block_on_slab();
  if (incline.gentle) settle(bodies, step, options);
  World world(bodies, step, options);
  WorldIntersections census(world);
  const double start = base_x(world, 1);
  Slide slide;
  for (int f = 0; f < incline.frames; ++f) {
    world.set_gravity(tilted_gravity(incline_angle(incline, f)));
    world.step();
    if (census.count().any()) ++slide.intersecting_frames;
  }
  slide.distance = base_x(world, 1) - start;
  slide.coulomb = coulomb_distance(incline);
  return slide;
}

void expect_held(const Incline& incline) {
  const Slide slide = slide_on_incline(incline);
  testing::Test::RecordProperty("slid_m", std::to_string(slide.distance));
  EXPECT_LT(std::abs(slide.distance), 0.01)
      << incline.degrees << " degrees, " << incline.friction_static << " / "
      << incline.friction_dynamic << ": slid " << slide.distance << " m in "
      << incline.frames / static_cast<double>(kFramesPerSecond) << " s";
  EXPECT_EQ(slide.intersecting_frames, 0u);
}

// Slides within `share` of Coulomb's distance, no frame intersecting.
void expect_coulomb(const Incline& incline, double share = 0.1) {
  const Slide slide = slide_on_incline(incline);
  ASSERT_GT(slide.coulomb, 0.0);
  testing::Test::RecordProperty("slid_m", std::to_string(slide.distance));
  testing::Test::RecordProperty("coulomb_m", std::to_string(slide.coulomb));
  EXPECT_NEAR(slide.distance, slide.coulomb, share * slide.coulomb)
      << incline.degrees << " degrees, " << incline.friction_static << " / "
      << incline.friction_dynamic << ": slid " << slide.distance << " m in "
      << incline.frames / static_cast<double>(kFramesPerSecond) << " s, Coulomb " << slide.coulomb
      << " m";
  EXPECT_EQ(slide.intersecting_frames, 0u);
}

TEST(FrictionIncline, StaticFrictionHoldsABlockTheDynamicAloneWouldNot) {
  // tan 28 = 0.53: above 0.45 (24.2 degrees), below 0.7 (35.0 degrees).
  expect_held({.degrees = 28.0, .friction_static = 0.7f, .friction_dynamic = 0.45f});
}

TEST(FrictionIncline, ASuddenLoadBeyondTheStaticConeBreaksItLooseForGood) {
  // Static angle 31.0 degrees, but tilted at once the block rings, and the net friction the tilt
  // asks of the slab rises to about 0.78 x the normal load within 0.1 s: it slips, and once it
  // slides dynamic 0.45 (below tan 28 = 0.53) never stops it. It slides as a block sliding from
  // the tilt would, 0.5 (g sin a - mu_d g cos a) t^2 = 1.415 m in 2 s (measured 1.452 m). Without
  // the stick/slide state it held (each substep's choice made afresh let its points stick again
  // between the rings).
  const Incline incline{.degrees = 28.0, .friction_static = 0.6f, .friction_dynamic = 0.45f};
  const Slide slide = slide_on_incline(incline);
  const double a = incline.degrees * std::numbers::pi / 180.0;
  const double t = incline.frames / static_cast<double>(kFramesPerSecond);
  const double sliding =
      0.5 * kGravity * (std::sin(a) - incline.friction_dynamic * std::cos(a)) * t * t;
  EXPECT_NEAR(slide.distance, sliding, 0.1 * sliding) << "slid " << slide.distance << " m in 2 s";
  EXPECT_EQ(slide.intersecting_frames, 0u);
}

TEST(FrictionIncline, ABlockJustAboveItsStaticAngleSlidesAsCoulombSays) {
  // Static angle 26.6 degrees; Coulomb's 1.415 m in 2 s (before: 0.93 m).
  expect_coulomb({.degrees = 28.0, .friction_static = 0.5f, .friction_dynamic = 0.45f});
}

TEST(FrictionIncline, FromAGentleStartABlockJustBelowItsStaticAngleHolds) {
  // Static angle 28.8 degrees: under the sudden tilt the block rings past it and slides.
  expect_held(
      {.degrees = 28.0, .friction_static = 0.55f, .friction_dynamic = 0.45f, .gentle = true});
}

TEST(FrictionIncline, FromAGentleStartABlockJustAboveItsStaticAngleSlides) {
  // Static angle 26.6 degrees. Before edge pairs whose closest point is an edge's end over a face
  // of the other surface were left to the vertex-face pairs, their slanted normals held it
  // (0.33 mm in 2 s); without the stick/slide state it slid 12 % short of Coulomb's 1.415 m (its
  // slow start stopped by the static cone substep after substep). Measured 1.301 m (-8.1 %).
  expect_coulomb(
      {.degrees = 28.0, .friction_static = 0.5f, .friction_dynamic = 0.45f, .gentle = true});
}

// Tilted over a second (World::set_gravity every frame) instead of at once: no step load, the
// slope's load grows as a tilting platform's does, and Coulomb's distance is integrated over
// the tilt (coulomb_distance). 3 s in all.
TEST(FrictionIncline, TiltedGraduallyABlockJustBelowItsStaticAngleHolds) {
  // Static angle 28.8 degrees, 0.8 above the slope: it slid 1.04 m tilted at once.
  expect_held({.degrees = 28.0,
               .friction_static = 0.55f,
               .friction_dynamic = 0.45f,
               .frames = 180,
               .ramp_frames = 60});
}

TEST(FrictionIncline, TiltedGraduallyABlockJustAboveItsStaticAngleSlides) {
  // Static angle 26.6 degrees, passed 0.95 s into the tilt: Coulomb's 1.494 m by 3 s; measured
  // 1.403 m (-6.1 %). Without the stick/slide state kept across substeps it broke away late and
  // slowly, 1.338 m (-10.4 %; docs/notes/2026-12-05-friction-tilt.md).
  expect_coulomb({.degrees = 28.0,
                  .friction_static = 0.5f,
                  .friction_dynamic = 0.45f,
                  .frames = 180,
                  .ramp_frames = 60});
}

TEST(FrictionIncline, TiltedGraduallyABlockJustPastItsStaticAngleSlides) {
  // Static angle 27.5 degrees, 0.5 below the slope, passed 0.98 s into the tilt: Coulomb's
  // 1.460 m by 3 s; measured 1.330 m (-8.9 %; without the stick/slide state 1.147 m, -21 %).
  expect_coulomb({.degrees = 28.0,
                  .friction_static = 0.52f,
                  .friction_dynamic = 0.45f,
                  .frames = 180,
                  .ramp_frames = 60});
}

// A block asleep on the level slab wakes when the slab tilts past its static angle (a change of
// gravity wakes every sleeping body: its rest was under the old load), and slides.
TEST(FrictionIncline, TiltingTheSlabWakesASleepingBlock) {
  StepSettings step;
  step.dt = 1.0f / kFramesPerSecond;
  step.substeps = 10;
  step.gravity = tilted_gravity(0.0);
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  options.response = incline_response(0.5f, 0.3f);
  options.response->sleep = SleepSettings{};
  World world(settled_block_on_slab(), step, options);
  int asleep_at = 0;
  for (int f = 1; f <= 60 && asleep_at == 0; ++f) {
    world.step();
    if (world.asleep(1)) asleep_at = f;
  }
  ASSERT_GT(asleep_at, 0) << "the settled block never fell asleep on the level slab";
  const double start = base_x(world, 1);
  world.set_gravity(tilted_gravity(35.0 * std::numbers::pi / 180.0));
  EXPECT_EQ(world.gravity(), tilted_gravity(35.0 * std::numbers::pi / 180.0));
  EXPECT_FALSE(world.asleep(1)) << "the tilt woke it before the next step";
  for (int f = 0; f < 30; ++f)
    world.step();
  EXPECT_FALSE(world.asleep(1));
  // Coulomb's 0.40 m in 0.5 s; woken, it slides as ASteepInclineSlidesAsCoulombSays does.
  EXPECT_GT(base_x(world, 1) - start, 0.3);
  EXPECT_THROW(world.set_gravity(glm::vec3(0.0f, NAN, 0.0f)), Error);
  EXPECT_EQ(world.gravity(), tilted_gravity(35.0 * std::numbers::pi / 180.0));
}

TEST(FrictionIncline, EqualCoefficientsSlideAsCoulombSays) {
  expect_coulomb({.degrees = 28.0, .friction_static = 0.45f, .friction_dynamic = 0.45f});
}

TEST(FrictionIncline, ASteepInclineSlidesAsCoulombSays) {
  // 1 s: Coulomb's 1.61 m, within the slab's 2 m.
  expect_coulomb(
      {.degrees = 35.0, .friction_static = 0.5f, .friction_dynamic = 0.3f, .frames = 60});
}

}  // namespace
}  // namespace deformcd
