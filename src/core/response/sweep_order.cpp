#include "core/response/sweep_order.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include <glm/common.hpp>

#include "deformcd/error.h"

namespace deformcd::response {

void SweepOrder::colour(std::span<const gpu::ContactPair> pairs,
                        std::span<const std::uint32_t> acting, std::uint32_t contacts,
                        std::span<const glm::vec3> positions) {
  if (contacts > acting.size()) {
    throw Error("SweepOrder: " + std::to_string(contacts) + " contacts of " +
                std::to_string(acting.size()) + " acting constraints");
  }
  const auto node_count = static_cast<std::uint32_t>(positions.size());
  for (const std::uint32_t p : acting) {
    if (p >= pairs.size()) {
      throw Error("SweepOrder: acting constraint " + std::to_string(p) + " of " +
                  std::to_string(pairs.size()));
    }
    for (const std::uint32_t n : pairs[p].nodes) {
      if (n >= node_count) {
        throw Error("SweepOrder: constraint " + std::to_string(p) + " names node " +
                    std::to_string(n) + " of " + std::to_string(node_count));
      }
      const glm::vec3& x = positions[n];
      if (!std::isfinite(x.x + x.y + x.z)) {
        throw Error("SweepOrder: constraint " + std::to_string(p) + "'s node " + std::to_string(n) +
                    " has a non-finite position");
      }
    }
  }
  // First fit never needs more colours than a constraint has neighbours plus one: at most
  // 4 x (the most constraints at one node - 1) + 1. per_node_ is all zero between calls: only
  // the acting constraints' nodes are counted, and cleared again (a projection's few thousand,
  // not every node).
  if (per_node_.size() != node_count) per_node_.assign(node_count, 0u);
  std::uint32_t most = 1;
  for (const std::uint32_t p : acting)
    for (const std::uint32_t n : pairs[p].nodes)
      most = std::max(most, ++per_node_[n]);
  for (const std::uint32_t p : acting)
    for (const std::uint32_t n : pairs[p].nodes)
      per_node_[n] = 0u;
  const std::uint32_t words = (4u * most + 63u) / 64u;
  if (words != words_ || node_count != node_count_) {
    words_ = words;
    node_count_ = node_count;
    taken_.assign(std::size_t{node_count} * words, 0u);
  }
  colour_.resize(acting.size());
  half_.resize(acting.size());
  runs_.clear();
  const auto size = static_cast<std::uint32_t>(acting.size());
  // The halves: split at the median of the acting constraints' first nodes along the longest
  // side of their box (one split for both groups, so that a node is in one half for all).
  // Where that leaves the smaller half less than a quarter of the constraints, the axis whose
  // smaller half holds the most: slab_drop's slab, two layers of nodes across its 3 mm, had
  // its acting part all across the longest side's split (half the constraints across, one half
  // empty: two threads 3-10 % slower than before the halves). Only then: the rule for every split
  // changed the order enough to undo half_overlap's untangling at frame 13 (c913b89).
  axis_ = 0;
  split_ = INFINITY;
  if (size > 0u) {
    glm::vec3 lo = positions[pairs[acting[0]].nodes[0]];
    glm::vec3 hi = lo;
    for (const std::uint32_t p : acting) {
      lo = glm::min(lo, positions[pairs[p].nodes[0]]);
      hi = glm::max(hi, positions[pairs[p].nodes[0]]);
    }
    const glm::vec3 side = hi - lo;
    const int longest = side.x >= side.y && side.x >= side.z ? 0 : (side.y >= side.z ? 1 : 2);
    std::uint32_t best = 0;
    for (int k = 0; k < 3; ++k) {
      const int axis = (longest + k) % 3;
      const float split = median_split(pairs, acting, positions, axis);
      const std::uint32_t smaller = smaller_half(pairs, acting, positions, axis, split);
      if (k == 0 || smaller > best) {
        best = smaller;
        axis_ = axis;
        split_ = split;
      }
      if (4u * best >= size) break;  // the longest side's split, unless its halves are too lopsided
    }
  }
  contact_colours_ = colour_group(pairs, acting, 0u, contacts, positions, 0u);
  const std::uint32_t colours =
      contact_colours_ + colour_group(pairs, acting, contacts, size, positions, contact_colours_);
  // Counting sort by colour and half, stable: each colour's first half, then its second, each
  // in acting order (a place across the halves counts as its colour's first).
  std::vector<std::uint32_t>& start = bucket_start_;
  start.assign(2u * colours + 1u, 0u);
  const auto bucket = [&](std::uint32_t a) { return 2u * colour_[a] + (half_[a] == 1u ? 1u : 0u); };
  for (std::uint32_t a = 0; a < size; ++a)
    ++start[bucket(a) + 1u];
  for (std::uint32_t b = 0; b < 2u * colours; ++b)
    start[b + 1u] += start[b];
  colour_begin_.resize(colours + 1u);
  half_begin_.resize(colours);
  for (std::uint32_t c = 0; c < colours; ++c) {
    colour_begin_[c] = start[2u * c];
    half_begin_[c] = start[2u * c + 1u];
  }
  colour_begin_[colours] = size;
  order_.resize(size);
  for (std::uint32_t a = 0; a < size; ++a)
    order_[start[bucket(a)]++] = a;
}

float SweepOrder::median_split(std::span<const gpu::ContactPair> pairs,
                               std::span<const std::uint32_t> acting,
                               std::span<const glm::vec3> positions, int axis) {
  const auto size = static_cast<std::uint32_t>(acting.size());
  keys_.resize(size);
  for (std::uint32_t a = 0; a < size; ++a)
    keys_[a] = positions[pairs[acting[a]].nodes[0]][axis];
  const auto middle = keys_.begin() + static_cast<std::ptrdiff_t>(size / 2u);
  std::nth_element(keys_.begin(), middle, keys_.end());
  return *middle;
}

std::uint32_t SweepOrder::smaller_half(std::span<const gpu::ContactPair> pairs,
                                       std::span<const std::uint32_t> acting,
                                       std::span<const glm::vec3> positions, int axis,
                                       float split) {
  std::uint32_t in_half[3] = {0u, 0u, 0u};
  for (const std::uint32_t p : acting)
    ++in_half[constraint_half(pairs[p], positions, axis, split)];
  return std::min(in_half[0], in_half[1]);
}

std::uint8_t SweepOrder::constraint_half(const gpu::ContactPair& pair,
                                         std::span<const glm::vec3> positions, int axis,
                                         float split) {
  std::uint32_t below = 0;
  for (const std::uint32_t n : pair.nodes)
    below += positions[n][axis] < split ? 1u : 0u;
  return below == 4u ? 0u : (below == 0u ? 1u : 2u);
}

std::uint32_t SweepOrder::colour_group(std::span<const gpu::ContactPair> pairs,
                                       std::span<const std::uint32_t> acting, std::uint32_t first,
                                       std::uint32_t end, std::span<const glm::vec3> positions,
                                       std::uint32_t base) {
  // Each constraint in the half of its nodes, or across the halves.
  if (first == end) return 0u;
  for (std::uint32_t a = first; a < end; ++a)
    half_[a] = constraint_half(pairs[acting[a]], positions, axis_, split_);
  // The halves' colours first (they share no node, so one first fit colours both), then the
  // constraints across them.
  places_.clear();
  for (std::uint32_t a = first; a < end; ++a)
    if (half_[a] != 2u) places_.push_back(a);
  const std::uint32_t inner = first_fit(pairs, acting, places_, base);
  places_.clear();
  for (std::uint32_t a = first; a < end; ++a)
    if (half_[a] == 2u) places_.push_back(a);
  const std::uint32_t across = first_fit(pairs, acting, places_, base + inner);
  if (inner > 0u) runs_.push_back({base, base + inner, true});
  if (across > 0u) runs_.push_back({base + inner, base + inner + across, false});
  return inner + across;
}

std::uint32_t SweepOrder::first_fit(std::span<const gpu::ContactPair> pairs,
                                    std::span<const std::uint32_t> acting,
                                    std::span<const std::uint32_t> places, std::uint32_t base) {
  std::uint32_t colours = 0;
  for (const std::uint32_t a : places) {
    const gpu::ContactPair& pair = pairs[acting[a]];
    std::uint32_t c = 0;
    for (std::uint32_t w = 0; w < words_; ++w) {
      std::uint64_t taken = 0;
      for (const std::uint32_t n : pair.nodes)
        taken |= taken_[std::size_t{n} * words_ + w];
      if (taken != ~std::uint64_t{0}) {
        c = 64u * w + static_cast<std::uint32_t>(std::countr_one(taken));
        break;
      }
    }
    colour_[a] = base + c;
    colours = std::max(colours, c + 1u);
    for (const std::uint32_t n : pair.nodes)
      taken_[std::size_t{n} * words_ + c / 64u] |= std::uint64_t{1} << (c % 64u);
  }
  // Cleared for the next places and call: only the nodes these set.
  for (const std::uint32_t a : places)
    for (const std::uint32_t n : pairs[acting[a]].nodes)
      for (std::uint32_t w = 0; w < words_; ++w)
        taken_[std::size_t{n} * words_ + w] = 0u;
  return colours;
}

}  // namespace deformcd::response
