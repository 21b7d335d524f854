// The body-level sort and sweep returns exactly the pairs whose boxes overlap.

#include "core/collision/body_pairs.h"

#include <random>

#include <gtest/gtest.h>

#include "core/collision/broad_phase.h"

namespace deformcd::collision {
namespace {

TEST(BodyPairs, SortAndSweepEqualsTestingAllPairs) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> where(0.0f, 10.0f);
  std::uniform_real_distribution<float> size(0.1f, 1.5f);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<gpu::Box> boxes;
    for (int i = 0; i < 60; ++i) {
      const glm::vec3 lo(where(rng), where(rng) * 0.3f, where(rng) * 0.3f);
      const glm::vec3 hi = lo + glm::vec3(size(rng), size(rng), size(rng));
      boxes.push_back({glm::vec4(lo, 0.0f), glm::vec4(hi, 0.0f)});
    }
    boxes[5] = empty_box();  // a body without faces
    boxes[9] = boxes[3];     // identical boxes, and touching ones
    boxes[10] = {glm::vec4(glm::vec3(boxes[3].max), 0.0f),
                 glm::vec4(glm::vec3(boxes[3].max) + 1.0f, 0.0f)};
    std::vector<gpu::BodyPair> expected;
    for (std::uint32_t a = 0; a < boxes.size(); ++a)
      for (std::uint32_t b = a + 1; b < boxes.size(); ++b)
        if (boxes_overlap(boxes[a], boxes[b])) expected.push_back({a, b});
    const std::vector<gpu::BodyPair> found = overlapping_body_pairs(boxes);
    ASSERT_EQ(found.size(), expected.size()) << trial;
    for (std::size_t i = 0; i < found.size(); ++i) {
      EXPECT_EQ(found[i].a, expected[i].a);
      EXPECT_EQ(found[i].b, expected[i].b);
    }
    EXPECT_GT(found.size(), 10u);
    EXPECT_LT(found.size(), 60u * 59u / 2u / 2u);  // the sweep skips most pairs
  }
}

}  // namespace
}  // namespace deformcd::collision
