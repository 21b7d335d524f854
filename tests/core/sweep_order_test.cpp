// The sweep's colours (response::SweepOrder): no two constraints of a colour share a node, the
// contacts' colours come before the volume constraints', each colour lists its constraints in
// acting order, and first fit gives each the lowest colour its nodes leave free.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

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
  ASSERT_EQ(order.size(), acting.size());
  ASSERT_FALSE(begin.empty());
  ASSERT_EQ(begin.front(), 0u);
  ASSERT_EQ(begin.back(), acting.size());
  std::vector<std::uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t a = 0; a < sorted.size(); ++a)
    ASSERT_EQ(sorted[a], a) << "a permutation";
  for (std::size_t c = 0; c + 1u < begin.size(); ++c) {
    ASSERT_LT(begin[c], begin[c + 1u]) << "colour " << c << " is empty";
    std::set<std::uint32_t> nodes;
    for (std::uint32_t e = begin[c]; e < begin[c + 1u]; ++e) {
      const std::uint32_t a = order[e];
      EXPECT_EQ(a < contacts, c < s.contact_colours()) << "place " << a << " in colour " << c;
      if (e > begin[c]) {
        EXPECT_LT(order[e - 1u], a) << "colour " << c << " out of acting order";
      }
      for (const std::uint32_t n : pairs[acting[a]].nodes)
        EXPECT_TRUE(nodes.insert(n).second) << "node " << n << " twice in colour " << c;
    }
  }
}

TEST(SweepOrder, FirstFitInActingOrder) {
  // Contacts 0-1 share node 1, 2 is apart; volume constraints 3-4 share node 5.
  const std::vector<gpu::ContactPair> pairs = {pair_of(0, 1, 2, 3), pair_of(1, 4, 5, 6),
                                               pair_of(7, 8, 9, 10), pair_of(0, 5, 11, 12),
                                               pair_of(5, 13, 14, 15)};
  const std::vector<std::uint32_t> acting = {0, 1, 2, 3, 4};
  response::SweepOrder s;
  s.colour(pairs, acting, 3u, 16u);
  EXPECT_EQ(s.contact_colours(), 2u);
  EXPECT_EQ(s.order(), (std::vector<std::uint32_t>{0, 2, 1, 3, 4}));
  EXPECT_EQ(s.colour_begin(), (std::vector<std::uint32_t>{0, 2, 3, 4, 5}));
  expect_a_valid_sweep(s, pairs, acting, 3u);
}

TEST(SweepOrder, RandomSetsAreValidAndTheSameEachTime) {
  std::mt19937 rng(7);
  for (int round = 0; round < 20; ++round) {
    const std::uint32_t nodes = 30u + static_cast<std::uint32_t>(rng() % 200u);
    std::vector<gpu::ContactPair> pairs;
    for (int p = 0; p < 400; ++p) {
      // Four different nodes, as every constraint has.
      std::set<std::uint32_t> n;
      while (n.size() < 4u)
        n.insert(static_cast<std::uint32_t>(rng() % nodes));
      const std::vector<std::uint32_t> v(n.begin(), n.end());
      pairs.push_back(pair_of(v[0], v[1], v[2], v[3]));
    }
    std::vector<std::uint32_t> acting;
    for (std::uint32_t p = 0; p < pairs.size(); ++p)
      if (rng() % 3u != 0u) acting.push_back(p);
    const auto contacts = static_cast<std::uint32_t>(acting.size() / 2u);
    response::SweepOrder s, again;
    s.colour(pairs, acting, contacts, nodes);
    expect_a_valid_sweep(s, pairs, acting, contacts);
    // A reused object (its scratch from this call) gives the same order.
    again.colour(pairs, {acting.data(), 5u}, 2u, nodes);
    again.colour(pairs, acting, contacts, nodes);
    EXPECT_EQ(again.order(), s.order());
    EXPECT_EQ(again.colour_begin(), s.colour_begin());
  }
}

TEST(SweepOrder, BadInputIsAnError) {
  const std::vector<gpu::ContactPair> pairs = {pair_of(0, 1, 2, 3)};
  response::SweepOrder s;
  EXPECT_THROW(s.colour(pairs, std::vector<std::uint32_t>{1u}, 0u, 4u), Error);
  EXPECT_THROW(s.colour(pairs, std::vector<std::uint32_t>{0u}, 0u, 3u), Error);
  EXPECT_THROW(s.colour(pairs, std::vector<std::uint32_t>{0u}, 2u, 4u), Error);
}

}  // namespace
}  // namespace deformcd
