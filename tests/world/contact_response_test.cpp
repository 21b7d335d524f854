// Contact response (issue 12) on the CPU backend, on the shipped response scenes: bodies that
// start overlapped come apart, a head-on impact conserves momentum and rebounds, and the
// proximity search behind it misses no pair a brute-force enumeration finds. (GL agrees with
// the CPU pass for pass: tests/gl/gl_contact_response_test.cpp; thread counts:
// tests/world/determinism_threads_test.cpp, which runs every shipped scene with its response.)

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
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

namespace fs = std::filesystem;

namespace deformcd {
namespace {

struct SceneWorld {
  std::vector<BodyInit> bodies;
  std::unique_ptr<World> world;
};

SceneWorld open_scene(const std::string& name, int frames, int threads = 0) {
  const Scene scene = read_scene(fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / (name + ".json"));
  SceneWorld out;
  out.bodies = make_scene_bodies(scene, read_tetgen, frames);
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  options.cpu_threads = threads;
  options.self_collision = scene.collision.self;
  options.response = scene.response;
  out.world = std::make_unique<World>(out.bodies, step_settings(scene.settings), options);
  return out;
}

double contour_length(const std::vector<Contact>& contacts) {
  double sum = 0.0;
  for (const Contact& c : contacts)
    sum += glm::length(c.segment[1] - c.segment[0]);
  return sum;
}

// Two bodies that start about 20 % overlapped come apart: no intersecting face pair after at
// most 60 frames, and none after that; the exact intersection contour's total length never
// grows once it has started to shrink.
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
  EXPECT_EQ(regrowth, 0.0) << "the contour grew back after shrinking; start " << start;
  RecordProperty("contour_start_m", std::to_string(start));
  RecordProperty("apart_from_frame", clear_from);
  RecordProperty("largest_regrowth_m", std::to_string(regrowth));
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
  std::uint64_t constraints = 0;
  for (int f = 0; f < kFrames; ++f) {
    world.step();
    EXPECT_EQ(world.contacts().size(), 0u) << "intersecting face pairs in frame " << f + 1;
    const ResponseCounts c = world.response_counts();
    constraints += c.vertex_face + c.edge_edge;
    worst = std::max(worst, glm::length(momentum().first - p0) / scale);
  }
  EXPECT_GT(constraints, 1000u) << "the bodies should have met";
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

// What the proximity search returns equals a brute-force enumeration of every vertex-triangle
// and edge-edge pair of the two meshes whose boxes, swept along each vertex's own motion and
// grown by their reaches (one per vertex; a primitive's is its vertices' largest), overlap, and
// whose distance less what the motions can close of it is within the sum of the reaches, on the
// impact scene's models at the moment of contact. One reach per mesh is the same as that reach
// on every vertex.
TEST(ContactResponse, ProximityEqualsBruteForce) {
  SceneWorld s = open_scene("impact", 40);
  // Up to the frame the response first finds many pairs: the bodies pressed together.
  for (int f = 0; f < 40; ++f) {
    s.world->step();
    const ResponseCounts c = s.world->response_counts();
    if (c.vertex_face + c.edge_edge > 2000u) break;
  }
  std::vector<CollisionMesh> meshes;
  std::vector<std::vector<glm::vec3>> positions;
  for (std::size_t b = 0; b < 2; ++b) {
    CollisionMesh m;
    m.vertex_count = static_cast<std::uint32_t>(s.bodies[b].body.positions.size());
    for (const gpu::Face& f : s.bodies[b].body.faces)
      m.triangles.push_back({f.a, f.b, f.c});
    meshes.push_back(std::move(m));
    positions.push_back(s.world->positions(b));
  }
  Detector detector(meshes, {.backend = BackendKind::kCpu});
  for (std::size_t b = 0; b < 2; ++b)
    detector.set_positions(b, std::span<const glm::vec3>(positions[b]));
  // A reach per vertex, around 6 mm on the armadillo and 9 mm on the lion.
  const float base[2] = {0.006f, 0.009f};
  std::vector<std::vector<float>> reach_of(2);
  std::vector<float> reach;
  for (std::size_t b = 0; b < 2; ++b) {
    for (std::size_t v = 0; v < positions[b].size(); ++v)
      reach_of[b].push_back(base[b] * (1.0f + 0.5f * std::sin(1.3f * static_cast<float>(v))));
    reach.insert(reach.end(), reach_of[b].begin(), reach_of[b].end());
  }
  const auto reach_most = [&](std::uint32_t b, std::initializer_list<std::uint32_t> v) {
    float most = 0.0f;
    for (const std::uint32_t i : v)
      most = std::max(most, reach_of[b][i]);
    return most;
  };
  // Every vertex moves: the bodies toward each other, and each vertex by its own wobble.
  std::vector<glm::vec3> motion;
  std::vector<std::vector<glm::vec3>> ends = positions;
  for (std::size_t b = 0; b < 2; ++b) {
    for (std::size_t v = 0; v < positions[b].size(); ++v) {
      const float wobble = 0.004f * std::sin(0.7f * static_cast<float>(v));
      const glm::vec3 m =
          (b == 0 ? glm::vec3(0.02f, 0.0f, 0.0f) : glm::vec3(-0.01f, 0.003f, 0.0f)) +
          glm::vec3(wobble, -wobble, 0.5f * wobble);
      motion.push_back(m);
      ends[b][v] += m;
    }
  }
  const std::vector<ProximityPair> found = detector.find_proximity(reach, motion);

  using Key = std::tuple<int, std::uint32_t, std::uint32_t, std::array<std::uint32_t, 4>>;
  // The box of vertices `v` of body b at both ends of their motion, grown by `grow`.
  const auto box = [&](std::uint32_t b, std::initializer_list<std::uint32_t> v, float grow) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const std::uint32_t i : v) {
      for (const glm::vec3& p : {positions[b][i], ends[b][i]}) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
      }
    }
    return std::pair{lo - grow, hi + grow};
  };
  const auto overlap = [](const std::pair<glm::vec3, glm::vec3>& a,
                          const std::pair<glm::vec3, glm::vec3>& b) {
    return glm::all(glm::lessThanEqual(a.first, b.second)) &&
           glm::all(glm::lessThanEqual(b.first, a.second));
  };
  // The distance filter (primitive_distance.h, tested against CGAL in test_primitive_distance).
  const auto within = [&](std::uint32_t kind, std::array<std::uint32_t, 2> body,
                          std::array<std::uint32_t, 4> v, float grow) {
    const std::uint32_t first_b = kind == gpu::kContactEdgeEdge ? 2u : 1u;
    glm::vec3 x[4], m[4];
    for (std::uint32_t k = 0; k < 4u; ++k) {
      const std::uint32_t b = body[k < first_b ? 0 : 1];
      x[k] = positions[b][v[k]];
      m[k] = ends[b][v[k]] - x[k];
    }
    return collision::primitives_within(kind, x, collision::closing_speed(kind, m), grow);
  };
  std::set<Key> expected;
  for (std::uint32_t a = 0; a < 2; ++a) {
    const std::uint32_t b = 1 - a;
    std::set<std::uint32_t> surface;
    for (const Triangle& t : meshes[a].triangles)
      surface.insert(t.begin(), t.end());
    for (const std::uint32_t v : surface) {
      const auto vbox = box(a, {v}, reach_of[a][v]);
      for (const Triangle& t : meshes[b].triangles) {
        const float reach_t = reach_most(b, {t[0], t[1], t[2]});
        if (overlap(vbox, box(b, {t[0], t[1], t[2]}, reach_t)) &&
            within(gpu::kContactVertexFace, {a, b}, {v, t[0], t[1], t[2]},
                   reach_of[a][v] + reach_t)) {
          expected.insert({0, a, b, {v, t[0], t[1], t[2]}});
        }
      }
    }
  }
  const auto edges = [](const CollisionMesh& m) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> out;
    for (const Triangle& t : m.triangles)
      for (int k = 0; k < 3; ++k)
        out.insert(std::minmax(t[k], t[(k + 1) % 3]));
    return out;
  };
  for (const auto& [a0, a1] : edges(meshes[0])) {
    const float reach_a = reach_most(0, {a0, a1});
    const auto abox = box(0, {a0, a1}, reach_a);
    for (const auto& [b0, b1] : edges(meshes[1])) {
      const float reach_b = reach_most(1, {b0, b1});
      if (overlap(abox, box(1, {b0, b1}, reach_b)) &&
          within(gpu::kContactEdgeEdge, {0u, 1u}, {a0, a1, b0, b1}, reach_a + reach_b))
        expected.insert({1, 0u, 1u, {a0, a1, b0, b1}});
    }
  }
  std::set<Key> got;
  for (const ProximityPair& p : found) {
    std::array<std::uint32_t, 4> v = p.vertices;
    if (p.kind == ProximityPair::Kind::kEdgeEdge) {
      // Edges in canonical (low, high) order, as the enumeration names them.
      if (v[0] > v[1]) std::swap(v[0], v[1]);
      if (v[2] > v[3]) std::swap(v[2], v[3]);
    }
    const bool inserted =
        got.insert({p.kind == ProximityPair::Kind::kEdgeEdge ? 1 : 0, p.mesh_a, p.mesh_b, v})
            .second;
    EXPECT_TRUE(inserted) << "a pair found twice";
  }
  EXPECT_GT(expected.size(), 100u) << "the models should be within reach";
  EXPECT_EQ(got.size(), expected.size());
  EXPECT_TRUE(got == expected);

  std::vector<float> spread;
  for (std::size_t b = 0; b < 2; ++b)
    spread.insert(spread.end(), positions[b].size(), base[b]);
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
  EXPECT_EQ(error_of(ResponseSettings{}), "");
}

}  // namespace
}  // namespace deformcd
