// Contact response (issue 12) on the CPU backend, on the shipped response scenes: bodies that
// start overlapped come apart, a head-on impact conserves momentum and rebounds without any
// intersection, the folding plate never intersects itself, and the
// proximity search behind it misses no pair a brute-force enumeration finds. (GL agrees with
// the CPU pass for pass: tests/gl/gl_contact_response_test.cpp; thread counts:
// tests/world/determinism_threads_test.cpp, which runs every shipped scene with its response.)

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/collision/primitive_distance.h"
#include "deformcd/detector.h"
#include "deformcd/error.h"
#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "deformcd/world.h"
#include "deformcd/world_intersections.h"
#include "support/collision_fixtures.h"
#include "support/sanitizers.h"
#include "world/contact_response.h"
#include "world/simulation_factory.h"

namespace fs = std::filesystem;

namespace deformcd {
namespace {

struct SceneWorld {
  std::vector<BodyInit> bodies;
  ResponseSettings world_response;
  std::unique_ptr<World> world;
};

// `shear` (0: none) shears the first body's start, x += shear y on each of its nodes; `edit`
// changes the scene before the world is built.
SceneWorld open_scene(const std::string& name, int frames, int threads = 0, float shear = 0.0f,
                      const std::function<void(Scene&)>& edit = {}) {
  Scene scene = read_scene(fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / (name + ".json"));
  if (edit) edit(scene);
  SceneWorld out;
  out.bodies = make_scene_bodies(scene, read_tetgen, frames);
  for (glm::vec4& x : out.bodies[0].body.positions)
    x.x += shear * x.y;
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  options.cpu_threads = threads;
  options.self_collision = scene.collision.self;
  options.response = scene.response;
  out.world_response = scene.response.value_or(ResponseSettings{});
  out.world = std::make_unique<World>(out.bodies, step_settings(scene.settings), options);
  return out;
}

// Contact constraints at the ends of frames, summed: the proximity pairs (vertex-face and
// edge-edge) and, of all contact constraints, those between two different bodies (with
// self-contact each body has its own near pairs in every frame, in contact or not).
struct ConstraintSums {
  std::uint64_t proximity = 0;
  std::uint64_t between_bodies = 0;
};

// Steps `frames` frames, expecting no intersecting face pair after any of them (the exact
// detector), and calls each_frame() after each; returns the constraints each frame ended with,
// summed. The intersection census (bodies with themselves included, vertices inside another
// body) is recorded, not asserted here (the tests that assert it say so).
template <class EachFrame>
ConstraintSums step_without_intersections(World& world, int frames, const EachFrame& each_frame) {
  WorldIntersections census(world);
  ConstraintSums constraints;
  int census_frames = 0;
  std::uint64_t most_self = 0, most_inside = 0;
  for (int f = 0; f < frames; ++f) {
    world.step();
    EXPECT_EQ(world.contacts().size(), 0u) << "intersecting face pairs in frame " << f + 1;
    const ResponseCounts c = world.response_counts();
    constraints.proximity += c.vertex_face + c.edge_edge;
    constraints.between_bodies += c.between_bodies;
    const IntersectionCensus counted = census.count();
    if (counted.any()) ++census_frames;
    most_self = std::max(most_self, counted.self_pairs);
    most_inside = std::max(most_inside, counted.inside_vertices);
    each_frame();
  }
  ::testing::Test::RecordProperty("census_intersecting_frames", census_frames);
  ::testing::Test::RecordProperty("census_most_self_pairs", std::to_string(most_self));
  ::testing::Test::RecordProperty("census_most_inside_vertices", std::to_string(most_inside));
  return constraints;
}

double contour_length(const std::vector<Contact>& contacts) {
  double sum = 0.0;
  for (const Contact& c : contacts)
    sum += glm::length(c.segment[1] - c.segment[0]);
  return sum;
}

// Two bodies that start about 20 % overlapped come apart: no intersecting face pair after at
// most 60 frames, and none after that; the exact intersection contour's total length never
// grows back, once it has started to shrink, by more than a thousandth of where it started (a
// frame where it holds still: since the volume constraints are watched from twice their floor,
// response::kVolumeWatch, it goes 449.80, 329.16, 329.22 mm and is gone at frame 3; before,
// 449.80, 343.05, 272.08, 169.01, 46.22 and gone at frame 5).
TEST(ContactResponse, OverlappedBodiesComeApart) {
  SceneWorld s = open_scene("overlap", 90);
  s.world->detect_collisions();
  const double start = contour_length(s.world->contacts());
  ASSERT_GT(start, 0.0) << "the scene should start overlapped";
  int clear_from = -1;
  double least = start;
  double regrowth = 0.0;  // once shrinking
  for (int f = 1; f <= 90; ++f) {
    s.world->step();
    const std::vector<Contact> contacts = s.world->contacts();
    const double length = contour_length(contacts);
    if (least < start) regrowth = std::max(regrowth, length - least);
    least = std::min(least, length);
    if (contacts.empty() && clear_from < 0) clear_from = f;
    if (!contacts.empty()) clear_from = -1;
  }
  EXPECT_GE(clear_from, 1) << "the bodies should end apart";
  EXPECT_LE(clear_from, 60) << "apart by frame 60 and for good";
  EXPECT_LE(regrowth, 1e-3 * start) << "the contour grew back after shrinking; start " << start;
  RecordProperty("contour_start_m", std::to_string(start));
  RecordProperty("apart_from_frame", clear_from);
  RecordProperty("largest_regrowth_m", std::to_string(regrowth));
}

// Half overlapped (scenes/half_overlap.json: overlap.json with the dragon 15 cm deeper, a
// quarter of each body's surface vertices inside the other), with the response's defaults
// (self-contact, the volume floor 0.3, motion-bounded substeps 0.3): the vertices inside are
// pushed out along the pair's way apart (deformcd/overlap.h), and the bodies come apart within a
// second: no triangle pair between them intersects and no vertex is inside the other from frame
// 20 on (measured: 11) through frame 90. Before the penetration constraints every one of 400
// frames intersected (issue 33). The crush that folds the bodies through themselves without the
// defaults (hundreds of self-intersecting pairs a frame) leaves a few while the bodies come apart
// (measured: up to 18 a frame; any change of the response moves them) and none from frame 13 on
// (measured: 13 with the three on, 12 without substep_motion). Two threads give the same
// positions bit for bit.
TEST(ContactResponse, HalfOverlappedBodiesComeApartWithinASecond) {
  constexpr int kFrames = 90;
  const auto run = [&](int threads, std::vector<glm::vec3>& last) {
    SceneWorld s = open_scene("half_overlap", kFrames, threads);
    WorldIntersections census(*s.world);
    const IntersectionCensus start = census.count();
    EXPECT_GT(start.inside_vertices, 200u) << "the scene should start deeply overlapped";
    int apart_from = -1;
    for (int f = 1; f <= kFrames; ++f) {
      s.world->step();
      if (f == 1) {
        EXPECT_GT(s.world->response_counts().penetrating, 200u);
      }
      const IntersectionCensus c = census.count();
      EXPECT_LE(c.self_pairs, f < 13 ? 20u : 0u) << "self-intersecting pairs in frame " << f;
      const bool apart = c.between_pairs == 0u && c.inside_vertices == 0u;
      if (apart && apart_from < 0) apart_from = f;
      if (!apart) apart_from = -1;
    }
    last = s.world->positions(1);
    return apart_from;
  };
  std::vector<glm::vec3> one, two;
  const int apart_from = run(1, one);
  RecordProperty("apart_from_frame", apart_from);
  EXPECT_GE(apart_from, 1) << "the bodies should end apart";
  EXPECT_LE(apart_from, 20) << "apart within a third of a second and for good";
  (void)run(2, two);
  EXPECT_TRUE(one == two) << "two threads against one";
}

// A free head-on impact without gravity, damping of the whole or fixed nodes, with zero total
// momentum: no face pair intersects in any frame (the exact detector), the response conserves
// momentum (mass splitting, momentum-conserving weights), and the bodies rebound with
// velocities of opposite signs along the impact axis (x).
TEST(ContactResponse, ImpactConservesMomentumAndRebounds) {
  constexpr int kFrames = 80;
  SceneWorld s = open_scene("impact", kFrames);
  World& world = *s.world;
  const auto momentum = [&] {
    glm::dvec3 p(0.0);
    double magnitude = 0.0;
    for (std::size_t b = 0; b < world.body_count(); ++b) {
      const std::vector<glm::vec3> v = world.velocities(b);
      for (std::size_t i = 0; i < v.size(); ++i) {
        const double m = s.bodies[b].body.node_mass[i];
        p += m * glm::dvec3(v[i]);
        magnitude += m * glm::length(glm::dvec3(v[i]));
      }
    }
    return std::pair{p, magnitude};
  };
  const auto [p0, scale] = momentum();
  double worst = 0.0;
  const ConstraintSums constraints = step_without_intersections(
      world, kFrames, [&] { worst = std::max(worst, glm::length(momentum().first - p0) / scale); });
  EXPECT_GT(constraints.between_bodies, 1000u) << "the bodies should have met";
  EXPECT_LT(worst, 1e-5) << "relative momentum drift";
  RecordProperty("momentum_drift", std::to_string(worst));
  const auto mean_vx = [&](std::size_t body) {
    double sum = 0.0;
    const std::vector<glm::vec3> v = world.velocities(body);
    for (const glm::vec3& x : v)
      sum += x.x;
    return sum / static_cast<double>(v.size());
  };
  EXPECT_LT(mean_vx(0), 0.0) << "the armadillo came from the left and goes back";
  EXPECT_GT(mean_vx(1), 0.0) << "the lion came from the right and goes back";
}

// The impact's clean run is not a lucky start: sheared by a few 1e-7 (x += k y on the
// armadillo's nodes), each run takes another path through the chaos (the contact patch differs
// by centimetres within 50 frames) and still no face pair intersects through the contact and
// the rebound. Before vertex-face constraints were kept to vertices that started a window in
// front of their face, these starts intersected in 2 to 28 frames of 120.
TEST(ContactResponse, ImpactStaysApartFromPerturbedStarts) {
#ifdef DEFORMCD_UNDER_ASAN
  const std::vector<float> shears = {2e-7f};  // 20x slower there
#else
  const std::vector<float> shears = {2e-7f, -3e-7f, 5e-7f};
#endif
  constexpr int kFrames = 60;  // the contact begins at frame 15; the bodies part by frame 60
  for (const float shear : shears) {
    SCOPED_TRACE("shear " + std::to_string(shear));
    SceneWorld s = open_scene("impact", kFrames, 0, shear);
    const ConstraintSums constraints = step_without_intersections(*s.world, kFrames, [] {});
    EXPECT_GT(constraints.between_bodies, 1000u) << "the bodies should have met";
  }
}

// The folding plate with self-contact response: its two halves swing down and meet below the
// fixed strip, and no two faces of the plate intersect in any frame (the exact self-detector).
TEST(ContactResponse, FoldingPlateNeverIntersectsItself) {
  constexpr int kFrames = 120;
  SceneWorld s = open_scene("fold_response", kFrames);
  const ConstraintSums constraints = step_without_intersections(*s.world, kFrames, [] {});
  // About 200 through frame 10, before the flaps meet; about 46,000 over the run.
  EXPECT_GT(constraints.proximity, 10000u) << "the halves should have met";
  RecordProperty("self_contact_constraints", std::to_string(constraints.proximity));
}

// A thin slab (10 x 10 x 0.3 cm, mean surface edge 6.7 mm) dropped on a plate whose edges are 11
// times its own comes to rest the slab's thickness above it (0.2 x its own mean edge: 1.35 mm),
// not the mean of the two thicknesses (8.2 mm, issue 33's "gaps show"), and no two triangles
// intersect in any frame, a body with itself included (the shipped scene has the volume floor).
TEST(ContactResponse, AThinSlabRestsOnACoarsePlateAtItsOwnThickness) {
  constexpr int kFrames = 90;
  SceneWorld s = open_scene("slab_drop", kFrames);
  const double slab = 0.2 * static_cast<double>(mean_surface_edge(s.bodies[1].body));
  const double base = 0.2 * static_cast<double>(mean_surface_edge(s.bodies[0].body));
  ASSERT_GT(base, 5.0 * slab) << "the plate's mesh should be much coarser than the slab's";
  WorldIntersections census(*s.world);
  for (int f = 0; f < kFrames; ++f) {
    s.world->step();
    const IntersectionCensus c = census.count();
    EXPECT_FALSE(c.any()) << "frame " << f + 1 << ": " << c.between_pairs << " pairs between, "
                          << c.self_pairs << " within a body, " << c.inside_vertices
                          << " vertices inside";
  }
  float top = -INFINITY, lowest = INFINITY;
  for (const glm::vec3& x : s.world->positions(0))
    top = std::max(top, x.y);
  for (const glm::vec3& x : s.world->positions(1))
    lowest = std::min(lowest, x.y);
  const double gap = static_cast<double>(lowest - top);
  EXPECT_GT(gap, 0.5 * slab);
  EXPECT_LT(gap, 1.5 * slab) << "the slab's thickness is " << slab << " m, the plate's " << base;
  RecordProperty("gap_m", std::to_string(gap));
}

// Steps `frames` frames, calling each_frame() after each, and returns the intersection census
// summed over them (each field the frames' total); with `until_intersection`, stops after the
// first frame with any intersection.
template <class EachFrame>
IntersectionCensus census_over(World& world, int frames, const EachFrame& each_frame,
                               bool until_intersection = false) {
  WorldIntersections census(world);
  IntersectionCensus sum;
  for (int f = 0; f < frames; ++f) {
    world.step();
    each_frame();
    const IntersectionCensus c = census.count();
    sum.between_pairs += c.between_pairs;
    sum.self_pairs += c.self_pairs;
    sum.inside_vertices += c.inside_vertices;
    if (until_intersection && c.between_pairs + c.self_pairs + c.inside_vertices > 0u) break;
  }
  return sum;
}

// Steps `frames` frames of `world` and expects no intersection of any kind after any of them:
// no triangle pair of a body with itself or between bodies, no vertex inside another body.
void expect_no_intersection_over(World& world, int frames) {
  const IntersectionCensus sum = census_over(world, frames, [] {});
  EXPECT_EQ(sum.self_pairs, 0u) << "self-intersecting pairs over the frames";
  EXPECT_EQ(sum.between_pairs, 0u) << "pairs between bodies";
  EXPECT_EQ(sum.inside_vertices, 0u) << "vertices inside another body";
}

// The impact with self-contact folds the armadillo through itself where the lion presses it:
// its tetrahedra turn inside out, and no contact between surfaces can undo that. With the
// volume floor (0.3) no two faces intersect in any frame, a body with itself included, and no
// vertex is inside another body, through frame 32 (the bodies meet at about frame 17); without it,
// the same frames have self-intersecting pairs (about 20 by frame 24). Two threads give the
// same positions bit for bit.
TEST(ContactResponse, AVolumeFloorKeepsTheImpactFromFoldingThroughItself) {
#ifdef DEFORMCD_UNDER_ASAN
  constexpr int kFrames = 20;
#else
  constexpr int kFrames = 32;
#endif
  const auto run = [&](float floor, int threads, std::vector<glm::vec3>* last) {
    SceneWorld s = open_scene("impact", kFrames, threads, 0.0f, [&](Scene& scene) {
      scene.collision.self = true;
      scene.response->volume_floor = floor;
    });
    const IntersectionCensus sum = census_over(*s.world, kFrames, [] {});
    if (last != nullptr) *last = s.world->positions(0);
    return sum;
  };
  std::vector<glm::vec3> one, two;
  const IntersectionCensus floored = run(0.3f, 1, &one);
  EXPECT_EQ(floored.self_pairs, 0u) << "self-intersecting pairs over the frames";
  EXPECT_EQ(floored.between_pairs, 0u) << "pairs between the bodies";
  EXPECT_EQ(floored.inside_vertices, 0u) << "vertices inside the other body";
#ifndef DEFORMCD_UNDER_ASAN
  const IntersectionCensus bare = run(0.0f, 1, nullptr);
  EXPECT_GT(bare.self_pairs, 20u) << "without the floor the armadillo should fold through itself";
  (void)run(0.3f, 2, &two);
  EXPECT_TRUE(one == two) << "two threads against one";
#endif
}

// The start of the 26-start study (deformcd.study --vary seed=0,...,25 --vary perturb=0.0001) that
// folded the lion through itself: seed 0 moves the armadillo by (2.74, -4.60, -9.18) and the
// lion by (-9.67, 6.27, 8.26) x 1e-5 m (numpy's default_rng(0), body by body). At frame 34 the
// lion's vertex 2471 slid under the edge 725-2469 of its face 1655 (a concave notch) and the
// edges of 2471's fan passed through that edge (4 self-intersecting pairs): the edge pair is
// 2.9 mm apart at rest, closer than the lion's thickness (6.7 mm), so it keeps half that
// distance, and the contacts held it below that window after window until the edges went
// through each other within a substep, where the closest points' difference turned over and
// the constraint held them crossed. Taken back along the side they started on
// (response::contact_geometry), no pair of any kind intersects through the contact.
TEST(ContactResponse, TheLionsSliversHoldFromTheStudysFoldingStart) {
  constexpr int kFrames = 36;
  SceneWorld s = open_scene("impact", kFrames, 0, 0.0f, [](Scene& scene) {
    scene.bodies[0].position +=
        glm::dvec3(2.739233746429087e-05, -4.604265724722594e-05, -9.180529521276106e-05);
    scene.bodies[1].position +=
        glm::dvec3(-9.669447289429419e-05, 6.265404784005448e-05, 8.255111545554435e-05);
  });
  expect_no_intersection_over(*s.world, kFrames);
}

// The pile (scenes/pile.json: twelve bodies dropped into a box) through its first landings: at
// frame 25, before edges that went through each other within a substep were taken back, three
// of "dragon 5"'s own triangle pairs intersected (faces 958 and 1022 against 1005 and 1038, two
// rings apart: a crushed patch whose surfaces crossed while every element kept a fifth of its
// volume). No pair of any kind intersects in any of the 30 frames.
TEST(ContactResponse, ThePileLandsWithoutFoldingThroughItself) {
  constexpr int kFrames = 30;
  SceneWorld s = open_scene("pile", kFrames);
  expect_no_intersection_over(*s.world, kFrames);
}

// The impact at six times its speed, with self-contact and the volume floor: 16 fixed
// substeps let the surfaces intersect (at four times, before the sweeps, up to 92 triangle
// pairs between the bodies and 43 vertices inside, frames 7-21); with motion-bounded substeps
// (substep_motion 0.3) the frames in contact take more (the counts say how many) and no two
// triangles intersect, a body with itself included, no vertex is inside the other body,
// through frame 24 (the bodies meet at frame 4). Before they meet the frames keep the scene's 16.
// Its self constraints crowd the nodes at the crushed front (a node in n constraints moves 1/n of
// what each asks): after the 8 Jacobi iterations asked for, contacts there were still deep, and the
// bodies went through each other at their first contact (49 pairs, frames 10-18) until the
// projections iterated on while one is deeper than half its thickness (response::contact_violated):
// some frames run more iterations than asked. Without self-contact the floor alone now keeps them
// apart at 16 substeps too (its tetrahedra iterated back above half their floor; 92 inverted in a
// frame against 10), so the contrast is made with self-contact on. At three times the speed (the
// issue's scene, in the census of docs/benchmarks.md) 16 fixed substeps hold too since the volume
// constraints are watched from twice their floor (response::kVolumeWatch: no pair between the
// bodies in 24 frames), hence four (the frames in contact then run 70-128 substeps, up to the cap,
// and most of them 32 iterations, kMaxIterationFactor x the 8 asked). Under the sanitizers
// (self-contact costs about 0.5 s a frame in release) the bounded run alone at three times the
// speed, without self-contact, over the first contact. Since the projection sweeps (Gauss-Seidel)
// 16 fixed substeps hold at four times the speed too (24 frames), so the contrast is made at
// six: there the fixed run folds the armadillo through itself (self-intersecting pairs in 11
// of 24 frames, none between the bodies) and the bounded one (up to 128 substeps) keeps every
// frame clean.
TEST(ContactResponse, MotionBoundedSubstepsKeepTheImpactAtSixTimesItsSpeedApart) {
#ifdef DEFORMCD_UNDER_ASAN
  constexpr int kFrames = 10;
  constexpr bool kSelfContact = false;
  constexpr double kSpeed = 3.0;
#else
  constexpr int kFrames = 24;
  constexpr bool kSelfContact = true;
  constexpr double kSpeed = 6.0;
#endif
  const auto run = [&](float motion, std::vector<std::uint64_t>& substeps, std::uint64_t& extended,
                       bool until_intersection = false) {
    SceneWorld s = open_scene("impact", kFrames, 0, 0.0f, [&](Scene& scene) {
      for (BodySpec& b : scene.bodies)
        b.velocity *= kSpeed;
      scene.collision.self = kSelfContact;
      scene.response->volume_floor = 0.3f;
      scene.response->substep_motion = motion;
    });
    World& world = *s.world;
    return census_over(
        world, kFrames,
        [&] {
          const ResponseCounts c = world.response_counts();
          substeps.push_back(c.substeps);
          if (c.iterations > 8u * c.substeps) ++extended;
        },
        until_intersection);
  };
  std::vector<std::uint64_t> bounded;
  std::uint64_t extended = 0;
  const IntersectionCensus sum = run(0.3f, bounded, extended);
  EXPECT_EQ(sum.between_pairs, 0u) << "pairs between the bodies over the frames";
  EXPECT_EQ(sum.self_pairs, 0u) << "self-intersecting pairs over the frames";
  EXPECT_EQ(sum.inside_vertices, 0u) << "vertices inside the other body";
  EXPECT_EQ(bounded.front(), 16u) << "apart, the scene's substeps";
  EXPECT_GT(*std::max_element(bounded.begin(), bounded.end()), 40u) << "in contact, more";
  EXPECT_LE(*std::max_element(bounded.begin(), bounded.end()), 16u * kMaxSubstepFactor);
  EXPECT_GT(extended, 0u) << "no frame ran more iterations than asked";
  RecordProperty("frames_with_more_iterations", std::to_string(extended));
#ifndef DEFORMCD_UNDER_ASAN
  std::vector<std::uint64_t> fixed;
  std::uint64_t fixed_extended = 0;
  // Any change of the response moves the count; the run stops at the first intersecting frame
  // (the frames after it, bodies deep in each other, cost most and show nothing more).
  const IntersectionCensus fixed_sum = run(0.0f, fixed, fixed_extended, true);
  EXPECT_GT(fixed_sum.between_pairs + fixed_sum.self_pairs + fixed_sum.inside_vertices, 0u)
      << "16 fixed substeps should let the surfaces intersect";
  EXPECT_TRUE(std::all_of(fixed.begin(), fixed.end(), [](auto n) { return n == 16u; }));
#endif
}

// Four bodies dropped in two columns onto a fixed base (scenes/stack.json; `lean`: with
// self-contact, the volume floor and motion-bounded substeps off): no face pair intersects in any
// of `frames` frames; the stack comes to rest: every body is asleep (the scene's sleep settings)
// by frame `asleep_by`, the kinetic energy at the end is below 1e-6 of its peak (the upper bodies
// landing), and from the frame the whole stack sleeps no body's centroid drifts (the issue's
// bound: 1 % of the mean surface edge a second).
void expect_the_stack_rests(bool lean, int frames, int asleep_by) {
#ifdef DEFORMCD_UNDER_ASAN
  // Under the sanitizers (20x slower here) the landings only: every body is on the base or on
  // another by frame 30.
  const int kFrames = 40;
#else
  const int kFrames = frames;
#endif
  SceneWorld s = open_scene("stack", frames, 0, 0.0f, [&](Scene& scene) {
    if (!lean) return;
    scene.collision.self = false;
    scene.response->volume_floor = 0.0f;
    scene.response->substep_motion = 0.0f;
  });
  World& world = *s.world;
  const auto kinetic_energy = [&] {
    double sum = 0.0;
    for (std::size_t b = 0; b < world.body_count(); ++b) {
      const std::vector<glm::vec3> v = world.velocities(b);
      for (std::size_t i = 0; i < v.size(); ++i)
        sum += 0.5 * s.bodies[b].body.node_mass[i] * glm::dot(glm::dvec3(v[i]), glm::dvec3(v[i]));
    }
    return sum;
  };
  const auto centroid = [&](std::size_t b) {
    glm::dvec3 sum(0.0);
    double mass = 0.0;
    const std::vector<glm::vec3> x = world.positions(b);
    for (std::size_t i = 0; i < x.size(); ++i) {
      sum += static_cast<double>(s.bodies[b].body.node_mass[i]) * glm::dvec3(x[i]);
      mass += s.bodies[b].body.node_mass[i];
    }
    return sum / mass;
  };
  const std::size_t n = world.body_count();
  double peak = 0.0;
  double last = 0.0;
  int frame = 0, all_asleep = 0;
  std::vector<glm::dvec3> rest_centroid(n), second_ago(n);
  const ConstraintSums constraints = step_without_intersections(world, kFrames, [&] {
    ++frame;
    last = kinetic_energy();
    peak = std::max(peak, last);
    if (frame == kFrames - 60)
      for (std::size_t b = 0; b < n; ++b)
        second_ago[b] = centroid(b);
    bool asleep = true;
    for (std::size_t b = 1; b < n; ++b)
      asleep = asleep && world.asleep(b);
    if (asleep && all_asleep == 0) {
      all_asleep = frame;
      for (std::size_t b = 0; b < n; ++b)
        rest_centroid[b] = centroid(b);
    }
  });
  EXPECT_GT(constraints.between_bodies, 100000u) << "the bodies should have landed";
  if (kFrames < frames) return;
  EXPECT_GT(all_asleep, 0) << "the stack never came to rest";
  EXPECT_LE(all_asleep, asleep_by) << "the stack came to rest late";
  EXPECT_LT(last, 1e-6 * peak) << "peak " << peak << " J";
  const double rest_time = static_cast<double>(kFrames - all_asleep) / 60.0;
  for (std::size_t b = 1; b < n && all_asleep > 0; ++b) {
    const double edge =
        world.contact_thickness(b) / static_cast<double>(s.world_response.relative_thickness);
    const double drift = glm::length(centroid(b) - rest_centroid[b]);
    EXPECT_LE(drift, 0.01 * edge * rest_time) << "body " << b << " drifted at rest";
    testing::Test::RecordProperty(
        "body" + std::to_string(b) + "_centroid_moved_over_the_last_second_m",
        std::to_string(glm::length(centroid(b) - second_ago[b])));
  }
  testing::Test::RecordProperty("kinetic_energy_ratio_at_the_end", std::to_string(last / peak));
  testing::Test::RecordProperty("frame_the_stack_fell_asleep", std::to_string(all_asleep));
}

// The scene with the three defaults against folding off, 240 frames (4 s): asleep by frame 210
// (197 measured; 160-171 with the Jacobi iterations the sweeps replaced: two of its bodies
// ring on longer, docs/notes/2026-12-07-gauss-seidel-probe.md). Without sleeping, the stack's
// energy at 3 s is 1e-5 to 4e-5 of its peak (docs/benchmarks.md).
TEST(ContactResponse, StackedBodiesComeToRestWithoutIntersecting) {
  expect_the_stack_rests(true, 240, 210);
}

// The scene as shipped, with the response's defaults (self-contact, the volume floor 0.3,
// motion-bounded substeps), 200 frames: asleep by frame 190 (measured: 162; 204 with the floor
// alone, before self-contact was on by default). The floor's pushes on the crushed bottom
// tetrahedra move nodes along the surface without a velocity; before static friction held positions
// (solve_contact's hold) and sleep was judged by the motion over a frame, the bottom bodies crept
// at 2-8 mm/s and the stack never slept (docs/notes/2026-12-05-hold.md).
TEST(ContactResponse, StackedBodiesWithTheDefaultsComeToRest) {
  expect_the_stack_rests(false, 200, 190);
}

// A pair as the brute-force enumeration names it: kind (0 vertex-triangle, 1 edge-edge), the
// meshes, the vertices; edges as (low, high), and within one mesh the lower edge first.
using PairKey = std::tuple<int, std::uint32_t, std::uint32_t, std::array<std::uint32_t, 4>>;

PairKey pair_key(int kind, std::uint32_t mesh_a, std::uint32_t mesh_b,
                 std::array<std::uint32_t, 4> v) {
  if (kind == 1) {
    if (v[0] > v[1]) std::swap(v[0], v[1]);
    if (v[2] > v[3]) std::swap(v[2], v[3]);
    if (mesh_a == mesh_b && std::pair{v[2], v[3]} < std::pair{v[0], v[1]}) {
      std::swap(v[0], v[2]);
      std::swap(v[1], v[3]);
    }
  }
  return {kind, mesh_a, mesh_b, v};
}

// Meshes at their positions, each vertex moving to `ends` and with its own reach.
struct ProximityWorld {
  std::vector<CollisionMesh> meshes;
  std::vector<std::vector<glm::vec3>> positions, ends;
  std::vector<std::vector<float>> reach_of;
};

// Every vertex-triangle and edge-edge pair of meshes a and b (a == b: one mesh with itself,
// leaving out a vertex with a triangle it is a corner of and edges sharing a vertex, each pair
// once) whose boxes, swept from the positions to the ends and grown by their reaches (a
// primitive's is its vertices' largest), overlap, and whose distance less what the motions can
// close of it is within the sum of the reaches.
std::set<PairKey> brute_force_proximity(const ProximityWorld& w, std::uint32_t a, std::uint32_t b) {
  const auto reach_most = [&](std::uint32_t m, std::initializer_list<std::uint32_t> v) {
    float most = 0.0f;
    for (const std::uint32_t i : v)
      most = std::max(most, w.reach_of[m][i]);
    return most;
  };
  // The box of vertices `v` of mesh m at both ends of their motion, grown by `grow`.
  const auto box = [&](std::uint32_t m, std::initializer_list<std::uint32_t> v, float grow) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const std::uint32_t i : v) {
      for (const glm::vec3& p : {w.positions[m][i], w.ends[m][i]}) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
      }
    }
    return std::pair{lo - grow, hi + grow};
  };
  const auto overlap = [](const std::pair<glm::vec3, glm::vec3>& p,
                          const std::pair<glm::vec3, glm::vec3>& q) {
    return glm::all(glm::lessThanEqual(p.first, q.second)) &&
           glm::all(glm::lessThanEqual(q.first, p.second));
  };
  // The distance filter (primitive_distance.h, tested against CGAL in test_primitive_distance).
  const auto within = [&](std::uint32_t kind, std::array<std::uint32_t, 2> mesh,
                          std::array<std::uint32_t, 4> v, float grow) {
    const std::uint32_t first_b = kind == gpu::kContactEdgeEdge ? 2u : 1u;
    glm::vec3 x[4], m[4];
    for (std::uint32_t k = 0; k < 4u; ++k) {
      const std::uint32_t i = mesh[k < first_b ? 0 : 1];
      x[k] = w.positions[i][v[k]];
      m[k] = w.ends[i][v[k]] - x[k];
    }
    return collision::primitives_within(kind, x, collision::closing_speed(kind, m), grow);
  };
  const auto edges = [](const CollisionMesh& m) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> out;
    for (const Triangle& t : m.triangles)
      for (int k = 0; k < 3; ++k)
        out.insert(std::minmax(t[k], t[(k + 1) % 3]));
    return out;
  };
  const bool self = a == b;
  std::set<PairKey> expected;
  for (const auto& [v_mesh, t_mesh] :
       self ? std::vector<std::array<std::uint32_t, 2>>{{a, a}}
            : std::vector<std::array<std::uint32_t, 2>>{{a, b}, {b, a}}) {
    std::set<std::uint32_t> surface;
    for (const Triangle& t : w.meshes[v_mesh].triangles)
      surface.insert(t.begin(), t.end());
    for (const std::uint32_t v : surface) {
      const auto vbox = box(v_mesh, {v}, w.reach_of[v_mesh][v]);
      for (const Triangle& t : w.meshes[t_mesh].triangles) {
        if (self && (v == t[0] || v == t[1] || v == t[2])) continue;
        const float reach_t = reach_most(t_mesh, {t[0], t[1], t[2]});
        if (overlap(vbox, box(t_mesh, {t[0], t[1], t[2]}, reach_t)) &&
            within(gpu::kContactVertexFace, {v_mesh, t_mesh}, {v, t[0], t[1], t[2]},
                   w.reach_of[v_mesh][v] + reach_t)) {
          expected.insert(pair_key(0, v_mesh, t_mesh, {v, t[0], t[1], t[2]}));
        }
      }
    }
  }
  for (const auto& [a0, a1] : edges(w.meshes[a])) {
    const float reach_a = reach_most(a, {a0, a1});
    const auto abox = box(a, {a0, a1}, reach_a);
    for (const auto& [b0, b1] : edges(w.meshes[b])) {
      if (self &&
          (std::pair{b0, b1} <= std::pair{a0, a1} || a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1))
        continue;
      const float reach_b = reach_most(b, {b0, b1});
      if (overlap(abox, box(b, {b0, b1}, reach_b)) &&
          within(gpu::kContactEdgeEdge, {a, b}, {a0, a1, b0, b1}, reach_a + reach_b))
        expected.insert(pair_key(1, a, b, {a0, a1, b0, b1}));
    }
  }
  return expected;
}

// The pairs `found` as the enumeration names them; none twice.
std::set<PairKey> found_keys(const std::vector<ProximityPair>& found) {
  std::set<PairKey> got;
  for (const ProximityPair& p : found) {
    const int kind = p.kind == ProximityPair::Kind::kEdgeEdge ? 1 : 0;
    const bool inserted = got.insert(pair_key(kind, p.mesh_a, p.mesh_b, p.vertices)).second;
    EXPECT_TRUE(inserted) << "a pair found twice";
  }
  return got;
}

// Whether pair key k names a vertex of `widened` (mesh, vertex).
bool involves(const PairKey& k, const std::set<std::pair<std::uint32_t, std::uint32_t>>& widened) {
  const auto& [kind, mesh_a, mesh_b, v] = k;
  const std::uint32_t first_b = kind == 1 ? 2u : 1u;
  for (std::uint32_t i = 0; i < 4u; ++i)
    if (widened.count({i < first_b ? mesh_a : mesh_b, v[i]}) != 0) return true;
  return false;
}

// After detector.find_proximity() on w (meshes a and b): every 23rd vertex's reach tripled by
// widen_proximity(), with the meshes moved away since, gives exactly the brute-force pairs of
// the raised reaches that involve those vertices; with the last search's other pairs, all of
// them.
void expect_widening_equals_brute_force(Detector& detector, ProximityWorld& w, std::uint32_t a,
                                        std::uint32_t b,
                                        const std::vector<ProximityPair>& searched) {
  std::vector<std::uint32_t> vertices;
  std::vector<float> raised;
  std::set<std::pair<std::uint32_t, std::uint32_t>> widened;
  std::uint32_t first = 0;
  for (std::uint32_t m = 0; m < w.meshes.size(); ++m) {
    for (std::uint32_t v = 0; v < w.positions[m].size(); v += 23u) {
      vertices.push_back(first + v);
      w.reach_of[m][v] *= 3.0f;
      raised.push_back(w.reach_of[m][v]);
      widened.insert({m, v});
    }
    first += static_cast<std::uint32_t>(w.positions[m].size());
  }
  // The detector searched the positions it had then: moving the meshes changes nothing.
  std::vector<std::vector<glm::vec3>> moved = w.positions;
  for (std::uint32_t m = 0; m < w.meshes.size(); ++m) {
    for (glm::vec3& x : moved[m])
      x += glm::vec3(0.5f, -0.25f, 0.125f);
    detector.set_positions(m, std::span<const glm::vec3>(moved[m]));
  }
  const std::set<PairKey> expected = brute_force_proximity(w, a, b);
  std::set<PairKey> expected_widened, kept;
  for (const PairKey& k : expected)
    if (involves(k, widened)) expected_widened.insert(k);
  const std::vector<ProximityPair> found = detector.widen_proximity(vertices, raised);
  const std::set<PairKey> got = found_keys(found);
  EXPECT_GT(expected_widened.size(), 10u);
  EXPECT_EQ(got.size(), expected_widened.size());
  EXPECT_TRUE(got == expected_widened);
  std::set<PairKey> all = got;
  for (const PairKey& k : found_keys(searched))
    if (!involves(k, widened)) all.insert(k);
  EXPECT_TRUE(all == expected) << "the search's other pairs with the widened ones";
  // Each pair's distance is its primitives' on the searched positions.
  for (const ProximityPair& p : found) {
    const std::uint32_t first_b = p.kind == ProximityPair::Kind::kEdgeEdge ? 2u : 1u;
    glm::vec3 x[4];
    for (std::uint32_t k = 0; k < 4u; ++k)
      x[k] = w.positions[k < first_b ? p.mesh_a : p.mesh_b][p.vertices[k]];
    const std::uint32_t kind =
        p.kind == ProximityPair::Kind::kEdgeEdge ? gpu::kContactEdgeEdge : gpu::kContactVertexFace;
    EXPECT_EQ(p.distance, collision::primitive_distance(kind, x));
  }
  EXPECT_THROW(
      (void)detector.widen_proximity(std::vector<std::uint32_t>{first}, std::vector<float>{0.01f}),
      InputError);
  EXPECT_THROW(
      (void)detector.widen_proximity(std::vector<std::uint32_t>{0u}, std::vector<float>{-1.0f}),
      InputError);
}

// A world's meshes and current positions, for a detector of their own.
ProximityWorld proximity_world(const SceneWorld& s, bool self_collision) {
  ProximityWorld w;
  w.meshes = test::surface_meshes(s.bodies, self_collision);
  for (std::size_t b = 0; b < s.bodies.size(); ++b)
    w.positions.push_back(s.world->positions(b));
  return w;
}

// What the proximity search returns equals a brute-force enumeration of every vertex-triangle
// and edge-edge pair of the two meshes whose boxes, swept along each vertex's own motion and
// grown by their reaches (one per vertex; a primitive's is its vertices' largest), overlap, and
// whose distance less what the motions can close of it is within the sum of the reaches, on the
// impact scene's models at the moment of contact. One reach per mesh is the same as that reach
// on every vertex.
TEST(ContactResponse, ProximityEqualsBruteForce) {
  // Without self-contact, so that the pairs counted below are the two bodies' (each body's own
  // near pairs alone are more than 2,000 in every frame).
  SceneWorld s =
      open_scene("impact", 40, 0, 0.0f, [](Scene& scene) { scene.collision.self = false; });
  // Up to the frame the response first finds many pairs: the bodies pressed together.
  for (int f = 0; f < 40; ++f) {
    s.world->step();
    const ResponseCounts c = s.world->response_counts();
    if (c.vertex_face + c.edge_edge > 2000u) break;
  }
  ProximityWorld w = proximity_world(s, false);
  Detector detector(w.meshes, {.backend = BackendKind::kCpu});
  for (std::size_t b = 0; b < 2; ++b)
    detector.set_positions(b, std::span<const glm::vec3>(w.positions[b]));
  // A reach per vertex, around 6 mm on the armadillo and 9 mm on the lion.
  const float base[2] = {0.006f, 0.009f};
  std::vector<float> reach;
  w.reach_of.resize(2);
  for (std::size_t b = 0; b < 2; ++b) {
    for (std::size_t v = 0; v < w.positions[b].size(); ++v)
      w.reach_of[b].push_back(base[b] * (1.0f + 0.5f * std::sin(1.3f * static_cast<float>(v))));
    reach.insert(reach.end(), w.reach_of[b].begin(), w.reach_of[b].end());
  }
  // Every vertex moves: the bodies toward each other, and each vertex by its own wobble.
  std::vector<glm::vec3> motion;
  w.ends = w.positions;
  for (std::size_t b = 0; b < 2; ++b) {
    for (std::size_t v = 0; v < w.positions[b].size(); ++v) {
      const float wobble = 0.004f * std::sin(0.7f * static_cast<float>(v));
      const glm::vec3 m =
          (b == 0 ? glm::vec3(0.02f, 0.0f, 0.0f) : glm::vec3(-0.01f, 0.003f, 0.0f)) +
          glm::vec3(wobble, -wobble, 0.5f * wobble);
      motion.push_back(m);
      w.ends[b][v] += m;
    }
  }
  const std::set<PairKey> expected = brute_force_proximity(w, 0, 1);
  const std::vector<ProximityPair> searched = detector.find_proximity(reach, motion);
  const std::set<PairKey> got = found_keys(searched);
  EXPECT_GT(expected.size(), 100u) << "the models should be within reach";
  EXPECT_EQ(got.size(), expected.size());
  EXPECT_TRUE(got == expected);
  {
    Detector widening(w.meshes, {.backend = BackendKind::kCpu});
    for (std::size_t b = 0; b < 2; ++b)
      widening.set_positions(b, std::span<const glm::vec3>(w.positions[b]));
    EXPECT_THROW(
        (void)widening.widen_proximity(std::vector<std::uint32_t>{0u}, std::vector<float>{0.01f}),
        Error);
    const std::vector<ProximityPair> first = widening.find_proximity(reach, motion);
    ProximityWorld raised = w;
    expect_widening_equals_brute_force(widening, raised, 0, 1, first);
  }

  std::vector<float> spread;
  for (std::size_t b = 0; b < 2; ++b)
    spread.insert(spread.end(), w.positions[b].size(), base[b]);
  EXPECT_TRUE(detector.find_proximity(base, motion) == detector.find_proximity(spread, motion));
  EXPECT_THROW((void)detector.find_proximity(std::vector<float>(3, 0.01f), motion), InputError);
  spread[7] = -1.0f;
  try {
    (void)detector.find_proximity(spread, motion);
    ADD_FAILURE() << "a negative reach should be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 7 has a reach of -1"), std::string::npos)
        << e.what();
  }
}

// Self-proximity equals the brute-force enumeration within one mesh: every vertex-triangle pair
// but a vertex with a triangle it is a corner of, every edge-edge pair but edges sharing a
// vertex (primitives of triangles that share only a corner are pairs), on the folding plate
// where its halves meet and its crease is crushed. Some of the pairs are of triangles sharing a
// corner, which the search once left out whole (faces_share_vertex).
TEST(ContactResponse, SelfProximityEqualsBruteForce) {
  SceneWorld s = open_scene("fold_response", 30);
  for (int f = 0; f < 30; ++f)
    s.world->step();
  ProximityWorld w = proximity_world(s, true);
  Detector detector(w.meshes, {.backend = BackendKind::kCpu});
  detector.set_positions(0, std::span<const glm::vec3>(w.positions[0]));
  // A reach per vertex around 9 mm (the plate's thickness is 8.9 mm), and a motion per vertex.
  std::vector<glm::vec3> motion;
  w.reach_of.resize(1);
  w.ends = w.positions;
  for (std::size_t v = 0; v < w.positions[0].size(); ++v) {
    const float i = static_cast<float>(v);
    w.reach_of[0].push_back(0.009f * (1.0f + 0.5f * std::sin(1.3f * i)));
    const float wobble = 0.004f * std::sin(0.7f * i);
    motion.emplace_back(wobble, -wobble, 0.5f * wobble * std::cos(i));
    w.ends[0][v] += motion.back();
  }
  const std::set<PairKey> expected = brute_force_proximity(w, 0, 0);
  const std::vector<ProximityPair> searched = detector.find_proximity(w.reach_of[0], motion);
  const std::set<PairKey> got = found_keys(searched);
  EXPECT_GT(expected.size(), 1000u) << "the plate should be folded onto itself";
  EXPECT_EQ(got.size(), expected.size());
  EXPECT_TRUE(got == expected);
  {
    ProximityWorld raised = w;
    expect_widening_equals_brute_force(detector, raised, 0, 0, searched);
  }
  // Vertex-triangle pairs whose vertex is one edge from a corner of the triangle: a triangle of
  // the vertex shares that corner with the triangle, so the search once left the pair out.
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const Triangle& t : w.meshes[0].triangles)
    for (int k = 0; k < 3; ++k)
      edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
  std::size_t neighbours = 0;
  for (const auto& [kind, mesh_a, mesh_b, v] : expected) {
    if (kind != 0) continue;
    for (std::size_t j = 1; j < 4; ++j) {
      if (edges.count(std::minmax(v[0], v[j])) != 0) {
        ++neighbours;
        break;
      }
    }
  }
  EXPECT_GT(neighbours, 0u);
  RecordProperty("pairs", static_cast<int>(expected.size()));
  RecordProperty("vertex_triangle_pairs_one_edge_apart", static_cast<int>(neighbours));
}

// A response backend that says a node strayed every `every`th projection, whether one did or
// not: the world then finds no stray to widen around and searches anew instead (the fallback
// of ContactResponse::widen, which a GPU rounding a deviation differently from the host could
// reach).
class StrayClaimingBackend : public response::ResponseBackend {
 public:
  StrayClaimingBackend(std::unique_ptr<response::ResponseBackend> inner, int every)
      : inner_(std::move(inner)), every_(every) {}
  void begin_frame(const response::FrameConstraints& c) override { inner_->begin_frame(c); }
  void update_frame(const response::FrameConstraints& c) override { inner_->update_frame(c); }
  bool project(const response::ContactConstants& k, int iterations) override {
    const bool strayed = inner_->project(k, iterations);
    return strayed || ++projections_ % every_ == 0;
  }
  [[nodiscard]] int last_iterations() const override { return inner_->last_iterations(); }

 private:
  std::unique_ptr<response::ResponseBackend> inner_;
  int every_;
  int projections_ = 0;
};

// The impact's first frames stepped as World::step does, with a backend that claims a stray
// every `every`th projection (0: never); returns the searches of the frames from `first` on,
// and expects no intersecting face pair in any frame.
std::uint64_t impact_searches(int every, int first, int frames) {
  const Scene scene = read_scene(fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / "impact.json");
  const std::vector<BodyInit> bodies = make_scene_bodies(scene, read_tetgen, 200);
  const SimulationState state = assemble_simulation(bodies);
  const StepSettings step = step_settings(scene.settings);
  const auto executor = std::make_shared<cpu::Executor>(2);
  const std::unique_ptr<sim::SimulationBackend> simulation =
      create_simulation(BackendKind::kCpu, nullptr, executor);
  simulation->upload(state);
  std::unique_ptr<response::ResponseBackend> backend =
      create_response(BackendKind::kCpu, nullptr, *simulation, executor);
  if (every > 0) backend = std::make_unique<StrayClaimingBackend>(std::move(backend), every);
  ContactResponse response(*scene.response, bodies, state, step, *simulation, std::move(backend),
                           executor, false);
  Detector detector(test::surface_meshes(bodies), {.backend = BackendKind::kCpu, .threads = 2});
  const glm::vec4* x = simulation->node_buffers().host_positions;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    detector.set_positions(b, HostPositions{&x[state.objects[b].node_offset].x, sizeof(glm::vec4)});
  const float h = step.dt / static_cast<float>(step.substeps);
  const sim::SubstepConstants constants{h, step.gravity, std::exp(-step.velocity_damping * h)};
  std::uint64_t searches = 0;
  for (int frame = 0; frame < frames; ++frame) {
    detector.detect();
    const std::vector<Contact> contacts = detector.contacts();
    EXPECT_TRUE(contacts.empty()) << "claims every " << every << ", frame " << frame;
    response.begin_frame(detector, contacts);
    for (int s = 0; s < step.substeps; ++s) {
      simulation->substep(constants);
      response.project(h, s + 1 < step.substeps);
    }
    if (frame >= first) searches += response.counts().searches;
  }
  EXPECT_GT(response.counts().vertex_face + response.counts().edge_edge, 100u)
      << "the bodies should be in contact by frame " << frames;
  return searches;
}

// When the backend says a node strayed and the host finds none beyond its reach (a GPU that
// rounds a deviation differently from the host could), the window is searched anew instead
// of widened: more searches than without the claims, and the bodies still never intersect.
TEST(ContactResponse, AStrayNoNodeMadeStartsANewSearch) {
  constexpr int kFirst = 12, kFrames = 24;
  const std::uint64_t plain = impact_searches(0, kFirst, kFrames);
  const std::uint64_t claimed = impact_searches(5, kFirst, kFrames);
  // 26 and 40 searches when written: many claims fall where a window ends or a node did stray.
  EXPECT_GT(claimed, plain + static_cast<std::uint64_t>(kFrames - kFirst) / 2u);
  RecordProperty("searches", static_cast<int>(plain));
  RecordProperty("searches_with_claims", static_cast<int>(claimed));
}

// Still meshes (find_proximity's `still`): the pairs between two of them, and a still mesh's
// pairs with itself, are not searched for; every other pair is the full search's, in its
// order, and a widening keeps to the same mesh pairs. On the overlap scene's two bodies as
// they start (20 % overlapped), each mesh also against itself.
TEST(ContactResponse, StillMeshesArePairedOnlyWithMovingOnes) {
  SceneWorld s = open_scene("overlap", 1);
  ProximityWorld w = proximity_world(s, true);
  const auto make_detector = [&] {
    Detector d(w.meshes, {.backend = BackendKind::kCpu, .threads = 2});
    for (std::size_t b = 0; b < 2; ++b)
      d.set_positions(b, std::span<const glm::vec3>(w.positions[b]));
    return d;
  };
  Detector detector = make_detector();
  const std::vector<float> reach = {0.01f, 0.01f};
  std::vector<glm::vec3> motion;
  for (std::size_t b = 0; b < 2; ++b)
    motion.insert(motion.end(), w.positions[b].size(), glm::vec3(b == 0 ? 0.01f : -0.01f, 0, 0));
  const auto without = [](const std::vector<ProximityPair>& pairs,
                          const std::vector<std::uint8_t>& still) {
    std::vector<ProximityPair> kept;
    for (const ProximityPair& p : pairs)
      if (still[p.mesh_a] == 0u || still[p.mesh_b] == 0u) kept.push_back(p);
    return kept;
  };
  const std::vector<ProximityPair> full = detector.find_proximity(reach, motion);
  for (const std::vector<std::uint8_t>& still :
       {std::vector<std::uint8_t>{1u, 0u}, std::vector<std::uint8_t>{0u, 1u},
        std::vector<std::uint8_t>{1u, 1u}, std::vector<std::uint8_t>{0u, 0u}}) {
    const std::string where = "still " + std::to_string(still[0]) + std::to_string(still[1]);
    const std::vector<ProximityPair> expected = without(full, still);
    EXPECT_TRUE(detector.find_proximity(reach, motion, still) == expected) << where;
    if (still[0] + still[1] == 1u) {
      EXPECT_GT(expected.size(), 1000u) << where;
      EXPECT_LT(expected.size(), full.size()) << where << ": each mesh has pairs with itself";
    }
    // A widening of every 7th vertex (reach doubled) after each search: the full search's
    // widening without the still meshes' pairs.
    std::vector<std::uint32_t> vertices;
    std::vector<float> raised;
    for (std::uint32_t v = 0; v < motion.size(); v += 7u) {
      vertices.push_back(v);
      raised.push_back(0.02f);
    }
    Detector other = make_detector();
    (void)other.find_proximity(reach, motion);
    const std::vector<ProximityPair> widened_full = other.widen_proximity(vertices, raised);
    (void)detector.find_proximity(reach, motion, still);
    EXPECT_TRUE(detector.widen_proximity(vertices, raised) == without(widened_full, still))
        << where;
  }
  const std::vector<std::uint8_t> three = {0u, 0u, 1u};
  EXPECT_THROW((void)detector.find_proximity(reach, motion, three), InputError);
}

TEST(ContactResponse, BadSettingsAreErrorsNamingTheField) {
  SceneWorld s = open_scene("overlap", 1);
  const auto error_of = [&](const ResponseSettings& settings) -> std::string {
    WorldOptions options;
    options.backend = BackendKind::kCpu;
    options.response = settings;
    try {
      World world(s.bodies, StepSettings{}, options);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  ResponseSettings r;
  r.thickness = std::nanf("");
  EXPECT_NE(error_of(r).find("thickness"), std::string::npos);
  r = {};
  r.friction_static = -0.5f;
  EXPECT_NE(error_of(r).find("friction_static"), std::string::npos);
  r = {};
  r.friction_dynamic = 0.9f;
  EXPECT_NE(error_of(r).find("friction_dynamic"), std::string::npos);
  r = {};
  r.restitution = 2.0f;
  EXPECT_NE(error_of(r).find("restitution"), std::string::npos);
  r = {};
  r.iterations = 0;
  EXPECT_NE(error_of(r).find("iterations"), std::string::npos);
  r = {};
  r.substep_motion = -1.0f;
  EXPECT_NE(error_of(r).find("substep_motion"), std::string::npos);
  r = {};
  r.volume_floor = 1.0f;
  EXPECT_NE(error_of(r).find("volume_floor must be below 1"), std::string::npos);
  EXPECT_EQ(error_of(ResponseSettings{}), "");
}

}  // namespace
}  // namespace deformcd
