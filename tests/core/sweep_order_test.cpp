// The sweep's colours (response::SweepOrder): no two constraints of a colour share a node, the
// contacts' colours come before the volume constraints', first fit gives each constraint the
// lowest colour its nodes leave free, and each group's two halves share no node across all of
// their run's colours (what lets the CPU sweep them on two threads with a sweep's bits).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include <glm/vec3.hpp>

#include "core/response/sweep_order.h"
#include "deformcd/error.h"

namespace deformcd {
namespace {

gpu::ContactPair pair_of(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  gpu::ContactPair p{};
  p.nodes[0] = a;
  p.nodes[1] = b;
  p.nodes[2] = c;
  p.nodes[3] = d;
  return p;
}

// Checks the order's invariants for `acting` (the first `contacts` of them contacts).
void expect_a_valid_sweep(const response::SweepOrder& s, const std::vector<gpu::ContactPair>& pairs,
                          const std::vector<std::uint32_t>& acting, std::uint32_t contacts) {
  const std::vector<std::uint32_t>& order = s.order();
  const std::vector<std::uint32_t>& begin = s.colour_begin();
  const std::vector<std::uint32_t>& half = s.half_begin();
  ASSERT_EQ(order.size(), acting.size());
  ASSERT_FALSE(begin.empty());
  ASSERT_EQ(half.size() + 1u, begin.size());
  ASSERT_EQ(begin.front(), 0u);
  ASSERT_EQ(begin.back(), acting.size());
  std::vector<std::uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t a = 0; a < sorted.size(); ++a)
    ASSERT_EQ(sorted[a], a) << "a permutation";
  for (std::size_t c = 0; c + 1u < begin.size(); ++c) {
    ASSERT_LT(begin[c], begin[c + 1u]) << "colour " << c << " is empty";
    ASSERT_LE(begin[c], half[c]);
    ASSERT_LE(half[c], begin[c + 1u]);
    std::set<std::uint32_t> nodes;
    for (std::uint32_t e = begin[c]; e < begin[c + 1u]; ++e) {
      const std::uint32_t a = order[e];
      EXPECT_EQ(a < contacts, c < s.contact_colours()) << "place " << a << " in colour " << c;
      if (e > begin[c] && e != half[c]) {
        EXPECT_LT(order[e - 1u], a) << "colour " << c << " out of acting order in a half";
      }
      for (const std::uint32_t n : pairs[acting[a]].nodes)
        EXPECT_TRUE(nodes.insert(n).second) << "node " << n << " twice in colour " << c;
    }
  }
  // The runs cover the colours in order; a run's halves share no node over all its colours,
  // and a colour outside a halves run is not split.
  std::uint32_t next = 0;
  for (const response::SweepOrder::Run& run : s.runs()) {
    ASSERT_EQ(run.first, next);
    ASSERT_LT(run.first, run.end);
    next = run.end;
    EXPECT_FALSE(run.first < s.contact_colours() && run.end > s.contact_colours())
        << "a run mixes contacts and volume constraints";
    std::set<std::uint32_t> first_half;
    for (std::uint32_t c = run.first; c < run.end; ++c) {
      if (!run.halves) {
        EXPECT_EQ(half[c], begin[c + 1u]) << "colour " << c << " of a run across the halves";
        continue;
      }
      for (std::uint32_t e = begin[c]; e < half[c]; ++e)
        for (const std::uint32_t n : pairs[acting[order[e]]].nodes)
          first_half.insert(n);
    }
    for (std::uint32_t c = run.first; run.halves && c < run.end; ++c)
      for (std::uint32_t e = half[c]; e < begin[c + 1u]; ++e)
        for (const std::uint32_t n : pairs[acting[order[e]]].nodes)
          EXPECT_EQ(first_half.count(n), 0u) << "node " << n << " in both halves of a run";
  }
  EXPECT_EQ(next, begin.size() - 1u);
}

// Nodes on the x axis, node n at x = n.
std::vector<glm::vec3> along_x(std::uint32_t nodes) {
  std::vector<glm::vec3> x(nodes);
  for (std::uint32_t n = 0; n < nodes; ++n)
    x[n] = glm::vec3(static_cast<float>(n), 0.0f, 0.0f);
  return x;
}

TEST(SweepOrder, HalvesFirstFitInActingOrderThenTheConstraintsAcrossThem) {
  // Nodes along x (node n at x = n); the acting constraints' first nodes (0, 1, 4, 10, 12, 9,
  // 3, 11, 13) have their median at 9. Contacts: 0, 1 and 2 below it (1 shares node 1 with 0;
  // 2 shares 2 with 0 and 6 with 1), 3 and 4 above it (sharing 13), 5 across (nodes 8 and 9).
  // Volume constraints: 6 below, 7 above, 8 across.
  const std::vector<gpu::ContactPair> pairs = {
      pair_of(0, 1, 2, 3),     pair_of(1, 5, 6, 7),     pair_of(4, 8, 6, 2),
      pair_of(10, 11, 13, 14), pair_of(12, 13, 15, 16), pair_of(9, 8, 17, 18),
      pair_of(3, 5, 0, 2),     pair_of(11, 14, 15, 19), pair_of(13, 8, 6, 17)};
  const std::vector<std::uint32_t> acting = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  response::SweepOrder s;
  s.colour(pairs, acting, 6u, along_x(20));
  // Colour 0: 0, then 3 (the second half); colour 1: 1, then 4; colour 2: 2; colour 3: 5, the
  // contact across. Colour 4: volume constraint 6, then 7; colour 5: 8, across.
  EXPECT_EQ(s.contact_colours(), 4u);
  EXPECT_EQ(s.order(), (std::vector<std::uint32_t>{0, 3, 1, 4, 2, 5, 6, 7, 8}));
  EXPECT_EQ(s.colour_begin(), (std::vector<std::uint32_t>{0, 2, 4, 5, 6, 8, 9}));
  EXPECT_EQ(s.half_begin(), (std::vector<std::uint32_t>{1, 3, 5, 6, 7, 9}));
  ASSERT_EQ(s.runs().size(), 4u);
  EXPECT_TRUE(s.runs()[0].halves);
  EXPECT_EQ(s.runs()[1].first, 3u);
  EXPECT_FALSE(s.runs()[1].halves);
  EXPECT_EQ(s.half_of(glm::vec3(8.5f, 0.0f, 0.0f)), 0u);
  EXPECT_EQ(s.half_of(glm::vec3(9.0f, 0.0f, 0.0f)), 1u);
  expect_a_valid_sweep(s, pairs, acting, 6u);
}

// A thin slab's layers far apart, its constraints (each joining both layers) along x: the box of
// their first nodes is longest across the layers, where every constraint would be across the
// halves (the smaller half empty); the split goes along x instead, where few are.
TEST(SweepOrder, AThinSlabIsSplitAlongItNotAcrossItsLayers) {
  std::vector<glm::vec3> x;
  for (std::uint32_t i = 0; i < 20u; ++i) {
    x.emplace_back(static_cast<float>(i), 0.0f, 0.0f);   // node 2 i: the lower layer
    x.emplace_back(static_cast<float>(i), 30.0f, 0.0f);  // node 2 i + 1: the upper
  }
  std::vector<gpu::ContactPair> pairs;
  std::vector<std::uint32_t> acting;
  for (std::uint32_t i = 0; i + 1u < 20u; ++i) {
    // The first node in either layer, so that the first nodes span 30 across and 18 along.
    pairs.push_back(i % 2u == 0u ? pair_of(2u * i, 2u * i + 1u, 2u * i + 2u, 2u * i + 3u)
                                 : pair_of(2u * i + 1u, 2u * i, 2u * i + 2u, 2u * i + 3u));
    acting.push_back(i);
  }
  response::SweepOrder s;
  s.colour(pairs, acting, 19u, x);
  expect_a_valid_sweep(s, pairs, acting, 19u);
  std::uint32_t in_halves = 0;
  for (const response::SweepOrder::Run& run : s.runs())
    if (run.halves) in_halves += s.colour_begin()[run.end] - s.colour_begin()[run.first];
  EXPECT_EQ(in_halves, 18u) << "one constraint across the split along x";
  EXPECT_EQ(s.half_of(glm::vec3(0.0f, 30.0f, 0.0f)), s.half_of(glm::vec3(0.0f, 0.0f, 0.0f)));
  EXPECT_NE(s.half_of(glm::vec3(0.0f, 0.0f, 0.0f)), s.half_of(glm::vec3(19.0f, 0.0f, 0.0f)));
}

// The longest side (x) keeps the split while its smaller half holds a quarter of the
// constraints, though y would hold more (the order, and so the physics, of scenes that split
// well along it stays as it was); below a quarter, y takes it. Constraint k: first node at
// x = k, its others up to `span` further along x, all four at y = 5 (k odd) or 0 (k even).
TEST(SweepOrder, TheLongestSideSplitsUnlessItsSmallerHalfHoldsUnderAQuarter) {
  for (const float span : {8.0f, 12.0f}) {
    std::vector<glm::vec3> x;
    std::vector<gpu::ContactPair> pairs;
    std::vector<std::uint32_t> acting;
    for (std::uint32_t k = 0; k < 40u; ++k) {
      const float y = k % 2u == 1u ? 5.0f : 0.0f;
      const auto first = static_cast<std::uint32_t>(x.size());
      for (const float along : {0.0f, span / 3.0f, 2.0f * span / 3.0f, span})
        x.emplace_back(static_cast<float>(k) + along, y, 0.0f);
      pairs.push_back(pair_of(first, first + 1u, first + 2u, first + 3u));
      acting.push_back(k);
    }
    response::SweepOrder s;
    s.colour(pairs, acting, 40u, x);
    expect_a_valid_sweep(s, pairs, acting, 40u);
    // Split at x = 20: with span 8 the constraints from k = 12 to 19 are across (12 below, 20
    // above: 12 >= 10); with span 12 from k = 8 (8 below: under a quarter).
    const bool along_x =
        s.half_of(glm::vec3(0.0f, 0.0f, 0.0f)) != s.half_of(glm::vec3(39.0f, 0.0f, 0.0f));
    const bool along_y =
        s.half_of(glm::vec3(0.0f, 0.0f, 0.0f)) != s.half_of(glm::vec3(0.0f, 5.0f, 0.0f));
    EXPECT_EQ(along_x, span == 8.0f) << "span " << span;
    EXPECT_EQ(along_y, span == 12.0f) << "span " << span;
  }
}

TEST(SweepOrder, RandomSetsAreValidAndTheSameEachTime) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
  for (int round = 0; round < 20; ++round) {
    const std::uint32_t nodes = 200u + static_cast<std::uint32_t>(rng() % 2000u);
    std::vector<glm::vec3> x(nodes);
    for (glm::vec3& p : x)
      p = glm::vec3(coordinate(rng), 0.1f * coordinate(rng), 0.1f * coordinate(rng));
    std::vector<gpu::ContactPair> pairs;
    for (int p = 0; p < 400; ++p) {
      // Four different nodes, as every constraint has; most of them near each other (a
      // window's constraints join neighbours), some anywhere.
      std::set<std::uint32_t> n;
      const std::uint32_t around = static_cast<std::uint32_t>(rng() % (nodes - 6u));
      while (n.size() < 4u) {
        n.insert(rng() % 32u == 0u ? static_cast<std::uint32_t>(rng() % nodes)
                                   : around + static_cast<std::uint32_t>(rng() % 6u));
      }
      const std::vector<std::uint32_t> v(n.begin(), n.end());
      pairs.push_back(pair_of(v[0], v[1], v[2], v[3]));
    }
    // Sorted along x, their box's longest side: near node numbers are near places.
    std::sort(x.begin(), x.end(), [](const glm::vec3& a, const glm::vec3& b) { return a.x < b.x; });
    std::vector<std::uint32_t> acting;
    for (std::uint32_t p = 0; p < pairs.size(); ++p)
      if (rng() % 3u != 0u) acting.push_back(p);
    const auto contacts = static_cast<std::uint32_t>(acting.size() / 2u);
    response::SweepOrder s, again;
    s.colour(pairs, acting, contacts, x);
    expect_a_valid_sweep(s, pairs, acting, contacts);
    // A reused object (its scratch from this call) gives the same order.
    again.colour(pairs, {acting.data(), 5u}, 2u, x);
    again.colour(pairs, acting, contacts, x);
    EXPECT_EQ(again.order(), s.order());
    EXPECT_EQ(again.colour_begin(), s.colour_begin());
    EXPECT_EQ(again.half_begin(), s.half_begin());
    // Most constraints in the halves: the split is worth two threads.
    std::uint32_t halves = 0;
    for (const response::SweepOrder::Run& run : s.runs())
      if (run.halves) halves += s.colour_begin()[run.end] - s.colour_begin()[run.first];
    EXPECT_GT(halves, acting.size() * 3u / 4u) << "round " << round;
  }
}

TEST(SweepOrder, BadInputIsAnError) {
  const std::vector<gpu::ContactPair> pairs = {pair_of(0, 1, 2, 3)};
  response::SweepOrder s;
  EXPECT_THROW(s.colour(pairs, std::vector<std::uint32_t>{1u}, 0u, along_x(4)), Error);
  EXPECT_THROW(s.colour(pairs, std::vector<std::uint32_t>{0u}, 0u, along_x(3)), Error);
  EXPECT_THROW(s.colour(pairs, std::vector<std::uint32_t>{0u}, 2u, along_x(4)), Error);
  std::vector<glm::vec3> x = along_x(4);
  x[2].y = NAN;
  try {
    s.colour(pairs, std::vector<std::uint32_t>{0u}, 1u, x);
    FAIL() << "a non-finite position was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("constraint 0's node 2 has a non-finite position"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace deformcd
