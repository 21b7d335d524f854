// Sleeping bodies (ResponseSettings::sleep) on the CPU backend: a block at rest on a fixed slab
// falls asleep and holds still; a second block dropped onto it wakes it (the island wakes before
// the blocks touch, when the search first joins them); the two settle and fall asleep together,
// never intersecting on the way; the same on 1 and 2 threads. (GL equals the CPU bit for bit on
// this world: tests/world/world_backends_test.cpp. The stack scene: contact_response_test.cpp.)

#include <algorithm>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "deformcd/error.h"
#include "deformcd/world.h"
#include "support/world_fixtures.h"
#include "world/body_sleep.h"

namespace deformcd {
namespace {

constexpr int kFrames = 240;

std::vector<glm::vec3> all_positions(const World& world) {
  std::vector<glm::vec3> out;
  for (std::size_t b = 0; b < world.body_count(); ++b) {
    const std::vector<glm::vec3> p = world.positions(b);
    out.insert(out.end(), p.begin(), p.end());
  }
  return out;
}

float lowest(const World& world, std::size_t body) {
  float y = INFINITY;
  for (const glm::vec3& p : world.positions(body))
    y = std::min(y, p.y);
  return y;
}

float highest(const World& world, std::size_t body) {
  float y = -INFINITY;
  for (const glm::vec3& p : world.positions(body))
    y = std::max(y, p.y);
  return y;
}

// BodySleep over `count` one-node bodies (node b is body b's), each free and allowed to sleep:
// slow below 0.5 m/s, asleep after 0.25 s, frames of 0.1 s.
BodySleep one_node_bodies(std::uint32_t count) {
  std::vector<gpu::ObjectInfo> objects(count, gpu::ObjectInfo{});
  for (std::uint32_t b = 0; b < count; ++b) {
    objects[b].node_offset = b;
    objects[b].node_count = 1u;
  }
  const SleepSettings settings{.speed = 0.5f, .time = 0.25f};
  return BodySleep(settings, objects, std::vector<float>(count, 1.0f),
                   std::vector<float>(count, 1.0f), std::vector<std::uint8_t>(count, 1u), 0.1f);
}

TEST(BodySleep, ARestingBlockSleepsWakesWhenABlockLandsOnItAndBothSleepTogether) {
  const std::vector<BodyInit> bodies = test::blocks_over_a_slab(3.0);
  World world(bodies, test::sleep_step(), test::sleep_options(BackendKind::kCpu, 1));
  int lower_slept = 0, woke = 0, both_slept = 0;
  std::vector<glm::vec3> held;  // the lower block's nodes while it first sleeps
  for (int f = 1; f <= kFrames; ++f) {
    world.step();
    ASSERT_EQ(world.contacts().size(), 0u) << "intersecting face pairs in frame " << f;
    const bool lower = world.asleep(1), upper = world.asleep(2);
    if (lower_slept == 0 && lower) {
      lower_slept = f;
      held = world.positions(1);
      EXPECT_FALSE(upper) << "the upper block is still falling";
      EXPECT_GT(lowest(world, 2), 1.0f) << "the upper block is still far above";
    }
    if (lower_slept != 0 && woke == 0) {
      if (lower) {
        // Asleep: its nodes hold still, bit for bit, at velocity 0.
        const std::vector<glm::vec3> now = world.positions(1);
        ASSERT_EQ(std::memcmp(now.data(), held.data(), held.size() * sizeof(glm::vec3)), 0)
            << "frame " << f;
        for (const glm::vec3& v : world.velocities(1))
          ASSERT_EQ(v, glm::vec3(0.0f)) << "frame " << f;
        // Its constraints with the fixed slab could correct nothing: left out, from the first
        // frame it starts asleep.
        if (f > lower_slept) {
          const ResponseCounts& counts = world.response_counts();
          EXPECT_EQ(counts.contact_constraints(), 0u) << "frame " << f;
        }
      } else {
        woke = f;
        // Woken by the search joining the blocks, before the upper block reaches it.
        EXPECT_GT(lowest(world, 2), highest(world, 1)) << "frame " << f;
      }
    }
    if (woke != 0) {
      // Linked by their contact, the blocks are one island: they sleep and wake together.
      EXPECT_EQ(lower, upper) << "frame " << f;
      if (both_slept == 0 && lower && upper) both_slept = f;
    }
  }
  EXPECT_GT(lower_slept, 0) << "the lower block never fell asleep";
  EXPECT_GT(woke, 0) << "the landing never woke the lower block";
  EXPECT_GT(both_slept, 0) << "the blocks never fell asleep together";
  EXPECT_TRUE(world.asleep(1) && world.asleep(2));
  EXPECT_FALSE(world.asleep(0)) << "a fixed body is never counted asleep";
  EXPECT_EQ(world.response_counts().asleep, 2u);
  // The upper block rests on the lower one, not beside it.
  EXPECT_GT(lowest(world, 2), highest(world, 1) - 0.01f);
  RecordProperty(
      "frames_lower_asleep_woken_both_asleep",
      std::to_string(lower_slept) + " " + std::to_string(woke) + " " + std::to_string(both_slept));
}

// Bodies that fell asleep in one island wake together, though the frames since linked them no
// more (the contact response does not search between two sleeping bodies), and a body that
// fell asleep alone sleeps on. One-node bodies: 0 and 1 resting on each other, 2 apart, 3
// moving until it hits 1.
TEST(BodySleep, AnIslandThatFellAsleepTogetherWakesTogether) {
  BodySleep sleep = one_node_bodies(4u);
  // Body 3 moves 0.3 m a frame (3 m/s); 0 jitters by 0.01 m a frame (slow) around a point.
  std::vector<glm::vec4> position(4, glm::vec4(0.0f));
  const auto frame_end = [&](int frame) {
    position[3].x = 0.3f * static_cast<float>(frame);
    position[0].y = frame % 2 == 0 ? 0.0f : 0.01f;
    return position;
  };
  const std::vector<std::pair<std::uint32_t, std::uint32_t>> resting = {{0u, 1u}};
  int frame = 0;
  // The first frame has no last one to be measured from: no body is slow yet.
  EXPECT_TRUE(sleep.end_frame(frame_end(frame++), resting).empty());
  for (int i = 0; i < 2; ++i)  // slow for 0.1 s, 0.2 s
    EXPECT_TRUE(sleep.end_frame(frame_end(frame++), resting).empty()) << "frame " << frame;
  // 0.3 s: the islands of the slow bodies sleep.
  EXPECT_EQ(sleep.end_frame(frame_end(frame++), resting), (std::vector<std::uint32_t>{0u, 1u, 2u}));
  // Asleep: no links between the sleeping bodies any more.
  for (int i = 0; i < 5; ++i)
    EXPECT_TRUE(sleep.end_frame(frame_end(frame++), {}).empty()) << "frame " << frame;
  // Body 3 reaches 1: 0 wakes with it, 2 sleeps on.
  EXPECT_EQ(sleep.end_frame(frame_end(frame++), {{1u, 3u}}), (std::vector<std::uint32_t>{0u, 1u}));
  EXPECT_TRUE(sleep.asleep(2));
  EXPECT_EQ(sleep.inverse_masses(0), std::vector<float>{1.0f});
  EXPECT_EQ(sleep.inverse_masses(2), std::vector<float>{0.0f});
}

// A body with a tetrahedron inside out is not at rest, however slowly it moves: it stays awake
// (its slow time counts from zero again) until the flag clears, then sleeps after the slow time,
// as a body that never had one. One-node bodies, both still: 0 flagged for four frames.
TEST(BodySleep, ABodyWithATetrahedronInsideOutStaysAwake) {
  BodySleep sleep = one_node_bodies(2u);
  const std::vector<glm::vec4> still(2, glm::vec4(0.0f));
  const std::vector<std::uint8_t> first_inverted = {1u, 0u}, none = {0u, 0u};
  int frame = 0;
  std::vector<int> fell_asleep(2, 0);
  for (; frame < 12; ++frame) {
    const std::vector<std::uint8_t>& inverted = frame < 4 ? first_inverted : none;
    for (const std::uint32_t b : sleep.end_frame(still, {}, inverted))
      if (sleep.asleep(b)) fell_asleep[b] = frame;
  }
  EXPECT_EQ(fell_asleep[1], 3) << "slow from frame 1: 0.3 s by frame 3";
  EXPECT_EQ(fell_asleep[0], 6) << "slow from frame 4, once the flag cleared: 0.3 s by frame 6";
  EXPECT_THROW(sleep.end_frame(still, {}, std::vector<std::uint8_t>{0u}), Error);
}

TEST(BodySleep, TheSameOnOneAndTwoThreads) {
  const std::vector<BodyInit> bodies = test::blocks_over_a_slab(3.0);
  std::vector<glm::vec3> end[2];
  for (int threads = 1; threads <= 2; ++threads) {
    World world(bodies, test::sleep_step(), test::sleep_options(BackendKind::kCpu, threads));
    for (int f = 0; f < kFrames; ++f)
      world.step();
    end[threads - 1] = all_positions(world);
  }
  ASSERT_EQ(end[0].size(), end[1].size());
  EXPECT_EQ(std::memcmp(end[0].data(), end[1].data(), end[0].size() * sizeof(glm::vec3)), 0);
}

TEST(BodySleep, BadSettingsAreErrorsNamingThem) {
  const std::vector<BodyInit> bodies = test::blocks_over_a_slab(0.0);
  for (const auto& [speed, time, key] :
       {std::tuple{0.0f, 0.25f, "sleep speed"}, std::tuple{NAN, 0.25f, "sleep speed"},
        std::tuple{0.5f, -1.0f, "sleep time"}, std::tuple{0.5f, INFINITY, "sleep time"}}) {
    WorldOptions options = test::sleep_options(BackendKind::kCpu, 1);
    options.response->sleep = SleepSettings{speed, time};
    try {
      World world(bodies, test::sleep_step(), options);
      ADD_FAILURE() << "expected an Error for " << key << " " << speed << " " << time;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace deformcd
