#include "core/response/sweep_order.h"

#include <algorithm>
#include <bit>

#include "deformcd/error.h"

namespace deformcd::response {

void SweepOrder::colour(std::span<const gpu::ContactPair> pairs,
                        std::span<const std::uint32_t> acting, std::uint32_t contacts,
                        std::uint32_t node_count) {
  if (contacts > acting.size()) {
    throw Error("SweepOrder: " + std::to_string(contacts) + " contacts of " +
                std::to_string(acting.size()) + " acting constraints");
  }
  // First fit never needs more colours than a constraint has neighbours plus one: at most
  // 4 x (the most constraints at one node - 1) + 1.
  per_node_.assign(node_count, 0u);
  std::uint32_t most = 1;
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
      most = std::max(most, ++per_node_[n]);
    }
  }
  const std::uint32_t words = (4u * most + 63u) / 64u;
  if (words != words_ || node_count != node_count_) {
    words_ = words;
    node_count_ = node_count;
    taken_.assign(std::size_t{node_count} * words, 0u);
  }
  colour_.resize(acting.size());
  const auto size = static_cast<std::uint32_t>(acting.size());
  contact_colours_ = colour_group(pairs, acting, 0u, contacts);
  const std::uint32_t volume_colours = colour_group(pairs, acting, contacts, size);
  // Counting sort by colour, stable: each colour's places in acting order.
  const std::uint32_t colours = contact_colours_ + volume_colours;
  colour_begin_.assign(colours + 1u, 0u);
  for (std::uint32_t a = 0; a < size; ++a) {
    const std::uint32_t c = a < contacts ? colour_[a] : contact_colours_ + colour_[a];
    colour_[a] = c;
    ++colour_begin_[c + 1u];
  }
  for (std::uint32_t c = 0; c < colours; ++c)
    colour_begin_[c + 1u] += colour_begin_[c];
  order_.resize(size);
  per_node_.assign(colours, 0u);  // reused as each colour's cursor
  for (std::uint32_t a = 0; a < size; ++a) {
    const std::uint32_t c = colour_[a];
    order_[colour_begin_[c] + per_node_[c]++] = a;
  }
}

std::uint32_t SweepOrder::colour_group(std::span<const gpu::ContactPair> pairs,
                                       std::span<const std::uint32_t> acting, std::uint32_t first,
                                       std::uint32_t end) {
  std::uint32_t colours = 0;
  for (std::uint32_t a = first; a < end; ++a) {
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
    colour_[a] = c;
    colours = std::max(colours, c + 1u);
    for (const std::uint32_t n : pair.nodes)
      taken_[std::size_t{n} * words_ + c / 64u] |= std::uint64_t{1} << (c % 64u);
  }
  // Cleared for the next group and call: only the nodes this group set.
  for (std::uint32_t a = first; a < end; ++a)
    for (const std::uint32_t n : pairs[acting[a]].nodes)
      for (std::uint32_t w = 0; w < words_; ++w)
        taken_[std::size_t{n} * words_ + w] = 0u;
  return colours;
}

}  // namespace deformcd::response
