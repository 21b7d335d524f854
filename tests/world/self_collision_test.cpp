// Self-collision through the World, on the CPU backend: the plate of scenes/fold.json folding
// into itself at its crease. Every broad phase returns exactly the pairs of an independent
// all-pairs self test written here (every pair of the body's faces, minus those sharing an
// edge, through the narrow phase), on every frame checked; the four paper models at rest have
// no self-contacts (no false positive among the thousands of faces sharing a node); contacts
// between bodies and within them come together; the output is the same for 1 and 2 threads.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/collision/face_pair_intersection.h"
#include "deformcd/body.h"
#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "deformcd/world.h"
#include "support/contact_compare.h"

namespace fs = std::filesystem;

namespace deformcd {
namespace {

constexpr BroadPhase kAllMethods[] = {BroadPhase::kBrute, BroadPhase::kOctree,
                                      BroadPhase::kOctreeCompact, BroadPhase::kBvh};

Scene shipped_scene(const std::string& name) {
  return read_scene(fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / (name + ".json"));
}

World scene_world(const Scene& scene, int frames, bool self, int threads = 0) {
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  options.broadphase = BroadPhase::kBvh;
  options.self_collision = self;
  options.cpu_threads = threads;
  return World(make_scene_bodies(scene, read_tetgen, frames), step_settings(scene.settings),
               options);
}

struct FacePairKey {
  std::uint32_t a;
  std::uint32_t b;
  bool operator==(const FacePairKey&) const = default;
};

// The independent oracle: every pair i < j of body 0's faces, minus those sharing an edge,
// through the narrow phase on the current positions.
std::vector<FacePairKey> all_pairs_self_test(const World& world) {
  const gpu::ObjectInfo& body = world.object(0);
  // The faces' nodes are global (into every body's nodes): body 0's positions from its
  // node_offset, read as mesh 0 (Face::body) by the narrow phase.
  const std::vector<glm::vec3> p = world.positions(0);
  std::vector<glm::vec4> positions(body.node_offset, glm::vec4(0.0f));
  for (const glm::vec3& x : p)
    positions.emplace_back(x, 0.0f);
  const collision::MeshVertices mesh{&positions[0].x, 4u};
  const gpu::Face* faces = world.faces().data() + body.face_offset;
  std::vector<FacePairKey> pairs;
  for (std::uint32_t i = 0; i < body.face_count; ++i) {
    for (std::uint32_t j = i + 1; j < body.face_count; ++j) {
      if (collision::shared_nodes(faces[i], faces[j]).count >= 2) continue;
      if (collision::face_pair_intersect(faces[i], faces[j], &mesh).intersect)
        pairs.push_back({i, j});
    }
  }
  return pairs;
}

std::vector<FacePairKey> self_pairs(const std::vector<Contact>& contacts) {
  std::vector<FacePairKey> pairs;
  for (const Contact& c : contacts) {
    if (c.a.body == c.b.body) pairs.push_back({c.a.face, c.b.face});
  }
  return pairs;
}

int shared_corners(const ContactFace& x, const ContactFace& y) {
  int n = 0;
  for (std::uint32_t u : x.nodes)
    for (std::uint32_t v : y.nodes)
      n += u == v ? 1 : 0;
  return n;
}

TEST(SelfCollision, EveryMethodEqualsTheAllPairsSelfTestOnTheFoldingPlate) {
  const Scene scene = shipped_scene("fold");
  ASSERT_EQ(scene.collision.self, true);
  World world = scene_world(scene, scene.settings.frames, true);
  int frames_in_contact = 0;
  int vertex_sharing = 0;
  for (int f = 0; f <= 60; ++f) {
    if (f > 0) world.step();
    // Frame 3: the plate bends gently at the crease, faces of its curved underside nearly
    // parallel and close (where a snapped vertex once made false contacts); then every 5th.
    if (f % 5 != 0 && f != 3) continue;
    const std::vector<FacePairKey> expected = all_pairs_self_test(world);
    frames_in_contact += expected.empty() ? 0 : 1;
    std::vector<Contact> first;
    for (BroadPhase method : kAllMethods) {
      world.set_broadphase(method);
      world.detect_collisions();
      const std::vector<Contact> contacts = world.contacts();
      ASSERT_EQ(self_pairs(contacts), expected) << broadphase_name(method) << ", frame " << f;
      ASSERT_EQ(contacts.size(), expected.size());
      for (const Contact& c : contacts) {
        EXPECT_LT(c.a.face, c.b.face);
        const int shared = shared_corners(c.a, c.b);
        EXPECT_LE(shared, 1) << "faces " << c.a.face << " and " << c.b.face << " share an edge";
        vertex_sharing += shared == 1 && method == BroadPhase::kBrute ? 1 : 0;
      }
      if (method == BroadPhase::kBrute) first = contacts;
      EXPECT_EQ(test::contacts_difference(contacts, first), "") << broadphase_name(method);
      EXPECT_EQ(world.collision_counts().contacts, contacts.size());
    }
  }
  // Frames 30 to 60 (the flaps crushed into each other at the crease); none while the plate
  // bends (0 to 25).
  EXPECT_EQ(frames_in_contact, 7);
  // The fold pushes neighbours of one node into each other: those contacts exist, and only
  // the shared-node test can find them.
  EXPECT_GT(vertex_sharing, 0);
}

TEST(SelfCollision, ThePaperModelsAtRestDoNotCollideWithThemselves) {
  // Closed, self-intersection-free surfaces: every face pair sharing a node touches there and
  // nowhere else, and edge neighbours are skipped.
  for (const char* model : {"armadillo", "bunny", "dragon", "lion"}) {
    BodyInit init;
    init.body = build_body(read_tetgen(fs::path(DEFORMCD_SOURCE_DIR) / "assets/models" / model));
    WorldOptions options;
    options.backend = BackendKind::kCpu;
    options.self_collision = true;
    for (BroadPhase method : kAllMethods) {
      options.broadphase = method;
      World world({init}, StepSettings{}, options);
      world.detect_collisions();
      EXPECT_EQ(world.contacts().size(), 0u) << model << ", " << broadphase_name(method);
      EXPECT_GT(world.collision_counts().candidates, 0u) << model;
    }
  }
}

TEST(SelfCollision, BodiesCollideWithEachOtherAndThemselvesInOnePass) {
  // Phase 1 with self-collision: the pair (armadillo, lion) as without it, plus each body's own
  // contacts, which its squashed start and the crossing may make; octree-compact agrees.
  const Scene scene = shipped_scene("phase1");
  constexpr int kFrames = 12;
  World with_self = scene_world(scene, kFrames, true);
  World without = scene_world(scene, kFrames, false);
  int between = 0;
  for (int f = 0; f <= kFrames; ++f) {
    if (f > 0) {
      with_self.step();
      without.step();
    }
    std::vector<Contact> others;
    for (const Contact& c : with_self.contacts()) {
      if (c.a.body != c.b.body) others.push_back(c);
    }
    ASSERT_EQ(test::contacts_difference(others, without.contacts()), "") << "frame " << f;
    between += static_cast<int>(others.size());
    if (f != 0 && f != kFrames / 2) continue;  // the leaf-box method: at rest and mid-crossing
    const std::vector<Contact> bvh = with_self.contacts();
    with_self.set_broadphase(BroadPhase::kOctreeCompact);
    with_self.detect_collisions();
    ASSERT_EQ(test::contacts_difference(with_self.contacts(), bvh), "") << "frame " << f;
    with_self.set_broadphase(BroadPhase::kBvh);
  }
  EXPECT_GT(between, 0);
}

TEST(SelfCollision, OutputIsTheSameForOneAndTwoThreads) {
  const Scene scene = shipped_scene("fold");
  World one = scene_world(scene, scene.settings.frames, true, 1);
  World two = scene_world(scene, scene.settings.frames, true, 2);
  std::size_t total = 0;
  for (int f = 1; f <= 40; ++f) {
    one.step();
    two.step();
    ASSERT_EQ(test::contacts_difference(one.contacts(), two.contacts()), "") << "frame " << f;
    total += one.contacts().size();
  }
  EXPECT_GT(total, 0u);
}

}  // namespace
}  // namespace deformcd
