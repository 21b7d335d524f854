// The per-element steps of the broad phases (core/collision/broad_phase.h).

#include "core/collision/broad_phase.h"

#include <gtest/gtest.h>

namespace deformcd::collision {
namespace {

gpu::Box box(glm::vec3 lo, glm::vec3 hi) {
  return {glm::vec4(lo, 0.0f), glm::vec4(hi, 0.0f)};
}

glm::uvec2 boxes(std::initializer_list<std::uint32_t> list) {
  glm::uvec2 bits(0u);
  for (std::uint32_t b : list)
    bits[b / 32u] |= 1u << (b % 32u);
  return bits;
}

TEST(BroadPhase, BoxesOverlapWhenClosedIntervalsMeet) {
  const gpu::Box a = box(glm::vec3(0), glm::vec3(1));
  EXPECT_TRUE(boxes_overlap(a, box(glm::vec3(0.5f), glm::vec3(2))));
  EXPECT_TRUE(boxes_overlap(a, box(glm::vec3(1, 0, 0), glm::vec3(2, 1, 1))));  // touching
  EXPECT_FALSE(boxes_overlap(a, box(glm::vec3(1.0001f, 0, 0), glm::vec3(2, 1, 1))));
  EXPECT_FALSE(boxes_overlap(a, box(glm::vec3(0, 0, -2), glm::vec3(1, 1, -0.5f))));
}

TEST(BroadPhase, AnEmptyBoxOverlapsNothingAndGrowsToItsPoints) {
  gpu::Box e = empty_box();
  EXPECT_FALSE(boxes_overlap(e, box(glm::vec3(-1e30f), glm::vec3(1e30f))));
  EXPECT_FALSE(boxes_overlap(e, e));
  grow_box(e, glm::vec3(1, 2, 3));
  grow_box(e, glm::vec3(-1, 5, 0));
  EXPECT_EQ(glm::vec3(e.min), glm::vec3(-1, 2, 0));
  EXPECT_EQ(glm::vec3(e.max), glm::vec3(1, 5, 3));
  EXPECT_EQ(e.min.w, 0.0f);
}

TEST(BroadPhase, AFacePairIsTestedFromItsFirstOverlappingBoxPairOnly) {
  const auto all = [](std::uint32_t, std::uint32_t) { return true; };
  // One box each: that pair is the first.
  EXPECT_TRUE(is_first_box_pair(boxes({7}), boxes({9}), 7, 9, all));
  // Face a in boxes 1 and 40 (the second word), face b in 2 and 3.
  const glm::uvec2 a = boxes({1, 40});
  const glm::uvec2 b = boxes({2, 3});
  EXPECT_TRUE(is_first_box_pair(a, b, 1, 2, all));
  EXPECT_FALSE(is_first_box_pair(a, b, 1, 3, all));
  EXPECT_FALSE(is_first_box_pair(a, b, 40, 2, all));
  EXPECT_FALSE(is_first_box_pair(a, b, 40, 3, all));
  // With (1, 2) and (1, 3) not overlapping, (40, 2) becomes the first.
  const auto some = [](std::uint32_t i, std::uint32_t j) {
    return !(i == 1 && (j == 2 || j == 3));
  };
  EXPECT_TRUE(is_first_box_pair(a, b, 40, 2, some));
  EXPECT_FALSE(is_first_box_pair(a, b, 40, 3, some));
  // Exactly one box pair of the four is first, whatever the mask.
  for (std::uint32_t mask = 0; mask < 16; ++mask) {
    const std::uint32_t ia[2] = {1, 40};
    const std::uint32_t jb[2] = {2, 3};
    const auto overlap = [&](std::uint32_t i, std::uint32_t j) {
      const std::uint32_t bit = (i == 40 ? 2u : 0u) + (j == 3 ? 1u : 0u);
      return ((mask >> bit) & 1u) != 0u;
    };
    int first = 0;
    for (std::uint32_t i : ia)
      for (std::uint32_t j : jb)
        if (overlap(i, j) && is_first_box_pair(a, b, i, j, overlap)) ++first;
    EXPECT_EQ(first, mask == 0 ? 0 : 1) << mask;
  }
}

}  // namespace
}  // namespace deformcd::collision
