// Collision detection through the World on the shipped scenes, on the CPU backend: the paper's
// octree and the broad phases beyond it (octree-compact, bvh) return exactly the pairs of the
// all-pairs baseline, on every frame.

#include <filesystem>
#include <set>

#include <gtest/gtest.h>

#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "deformcd/world.h"
#include "support/contact_compare.h"
#include "support/world_fixtures.h"

namespace fs = std::filesystem;

namespace deformcd {
namespace {

fs::path scene_path(const std::string& name) {
  return fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / (name + ".json");
}

// The scene's whole trajectory (apart, through each other, apart) in `frames` frames.
World scene_world(const std::string& name, int frames, BroadPhase method) {
  const Scene scene = read_scene(scene_path(name));
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  options.broadphase = method;
  return World(make_scene_bodies(scene, read_tetgen, frames), step_settings(scene.settings),
               options);
}

class CollisionOnScenes : public ::testing::TestWithParam<const char*> {};

TEST_P(CollisionOnScenes, EveryMethodEqualsBruteOnEveryFrame) {
  constexpr int kFrames = 24;
  constexpr BroadPhase kMethods[] = {BroadPhase::kOctree, BroadPhase::kOctreeCompact,
                                     BroadPhase::kBvh};
  World world = scene_world(GetParam(), kFrames, BroadPhase::kBrute);
  int frames_in_contact = 0;
  std::size_t peak = 0;
  std::vector<std::size_t> counts;
  for (int f = 0; f <= kFrames; ++f) {
    if (f > 0) world.step();
    world.set_broadphase(BroadPhase::kBrute);
    world.detect_collisions();
    const std::vector<Contact> brute = world.contacts();
    for (BroadPhase method : kMethods) {
      world.set_broadphase(method);
      world.detect_collisions();
      const std::vector<Contact> contacts = world.contacts();
      ASSERT_EQ(test::contacts_difference(contacts, brute), "")
          << broadphase_name(method) << ", frame " << f;

      const CollisionCounts method_counts = world.collision_counts();
      EXPECT_EQ(method_counts.contacts, contacts.size());
      std::set<std::pair<std::uint32_t, std::uint32_t>> faces;
      for (const Contact& c : contacts) {
        EXPECT_LT(c.a.body, c.b.body);
        faces.insert({c.a.body, c.a.face});
        faces.insert({c.b.body, c.b.face});
      }
      EXPECT_EQ(method_counts.colliding_faces, faces.size())
          << broadphase_name(method) << ", frame " << f;
      const std::vector<std::uint32_t> flags = world.face_flags();
      std::size_t flagged = 0;
      for (std::uint32_t v : flags)
        flagged += v != 0u ? 1 : 0;
      EXPECT_EQ(flagged, faces.size()) << broadphase_name(method) << ", frame " << f;
    }
    frames_in_contact += brute.empty() ? 0 : 1;
    peak = std::max(peak, brute.size());
    counts.push_back(brute.size());
  }
  // Apart at the start and the end, in contact in between.
  EXPECT_EQ(counts.front(), 0u);
  EXPECT_EQ(counts.back(), 0u);
  EXPECT_GE(frames_in_contact, 3);
  EXPECT_GE(peak, 50u);
  std::cout << GetParam() << ": " << frames_in_contact << " of " << kFrames + 1
            << " frames in contact, at most " << peak << " face pairs\n";
}

INSTANTIATE_TEST_SUITE_P(ShippedScenes, CollisionOnScenes, ::testing::Values("phase1", "phase2"));

// Sixteen bodies in two lanes crossing each other: the body-level sort and sweep keeps only the
// nearby pairs, and the beyond-paper methods still find exactly the contacts of testing all
// pairs (brute, too slow for every frame here, on the frame in the middle of the run).
TEST(CollisionOnScenesMany, BvhEqualsOctreeCompactEveryFrameAndBruteMidRun) {
  constexpr int kFrames = 12;
  World world = scene_world("crossing16", kFrames, BroadPhase::kBvh);
  ASSERT_EQ(world.body_count(), 16u);
  int frames_in_contact = 0;
  std::set<std::pair<std::uint32_t, std::uint32_t>> body_pairs_in_contact;
  for (int f = 0; f <= kFrames; ++f) {
    if (f > 0) world.step();
    world.set_broadphase(BroadPhase::kBvh);
    world.detect_collisions();
    const std::vector<Contact> bvh = world.contacts();
    world.set_broadphase(BroadPhase::kOctreeCompact);
    world.detect_collisions();
    ASSERT_EQ(test::contacts_difference(bvh, world.contacts()), "") << "frame " << f;
    if (f == kFrames / 2) {
      world.set_broadphase(BroadPhase::kBrute);
      world.detect_collisions();
      ASSERT_EQ(test::contacts_difference(bvh, world.contacts()), "") << "frame " << f;
    }
    frames_in_contact += bvh.empty() ? 0 : 1;
    for (const Contact& c : bvh)
      body_pairs_in_contact.insert({c.a.body, c.b.body});
  }
  EXPECT_GE(frames_in_contact, 4);
  // Each body meets only its oncoming neighbours: far fewer than all 120 pairs.
  EXPECT_GE(body_pairs_in_contact.size(), 8u);
  EXPECT_LE(body_pairs_in_contact.size(), 40u);
}

TEST(WorldCollision, OneBodyHasNoContacts) {
  World world = scene_world("hanging", 10, BroadPhase::kOctree);
  world.step();
  EXPECT_TRUE(world.contacts().empty());
  EXPECT_EQ(world.collision_counts().contacts, 0u);
}

TEST(WorldCollision, NoBroadPhaseDetectsNothing) {
  World world = scene_world("phase2", 24, BroadPhase::kNone);
  for (int f = 0; f < 12; ++f)
    world.step();  // in contact by now
  EXPECT_TRUE(world.contacts().empty());
  EXPECT_EQ(world.collision_counts().contacts, 0u);
  world.set_broadphase(BroadPhase::kOctree);
  world.detect_collisions();
  EXPECT_FALSE(world.contacts().empty());
}

TEST(WorldCollision, UnknownBroadPhaseNamesTheValidOnes) {
  try {
    (void)parse_broadphase("kdtree");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "unknown broad phase 'kdtree' (valid: none, brute, octree, octree-compact, bvh)");
  }
  EXPECT_EQ(parse_broadphase("octree"), BroadPhase::kOctree);
  EXPECT_EQ(broadphase_name(BroadPhase::kBrute), "brute");
}

}  // namespace
}  // namespace deformcd
