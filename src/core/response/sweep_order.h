#pragma once
// The order of a projection's Gauss-Seidel sweeps (contact_constraints.h): the acting
// constraints in colours, no two constraints of one colour sharing a node, so that a colour's
// constraints can be solved at once, in any order and on any number of threads (or GPU
// invocations), with the same result bit for bit. Colours are given first fit in the acting
// list's order (greedy colouring), the contacts apart from the volume constraints, which a sweep
// solves after them. Both response backends call this one function on the same acting list, so
// their sweeps are the same: the colours need no GPU colouring to agree.

#include <cstdint>
#include <span>
#include <vector>

#include "deformcd/gpu_layout.h"

namespace deformcd::response {

class SweepOrder {
 public:
  /// Colours the acting constraints: acting[a] indexes `pairs`; the first `contacts` entries
  /// are contacts, the rest volume constraints. Every node is below `node_count`.
  void colour(std::span<const gpu::ContactPair> pairs, std::span<const std::uint32_t> acting,
              std::uint32_t contacts, std::uint32_t node_count);

  /// Acting places (indices into the acting list), colour by colour (the contacts' colours
  /// first), each colour's in acting order.
  [[nodiscard]] const std::vector<std::uint32_t>& order() const { return order_; }
  /// Colour c's places are order()[colour_begin()[c], colour_begin()[c + 1]); one more entry
  /// than there are colours.
  [[nodiscard]] const std::vector<std::uint32_t>& colour_begin() const { return colour_begin_; }
  /// The first contact_colours() colours are the contacts'.
  [[nodiscard]] std::uint32_t contact_colours() const { return contact_colours_; }

 private:
  // Colours one group, acting[first, end), from colour 0 on; returns how many it used.
  std::uint32_t colour_group(std::span<const gpu::ContactPair> pairs,
                             std::span<const std::uint32_t> acting, std::uint32_t first,
                             std::uint32_t end);

  std::vector<std::uint32_t> order_;
  std::vector<std::uint32_t> colour_begin_;
  std::uint32_t contact_colours_ = 0;
  std::vector<std::uint32_t> colour_;  // per acting place
  // Per node, the colours its constraints of the group being coloured took: words_ 64-bit
  // words a node; all zero between calls (each group clears the nodes it set).
  std::vector<std::uint64_t> taken_;
  std::uint32_t words_ = 0;
  std::uint32_t node_count_ = 0;
  std::vector<std::uint32_t> per_node_;  // scratch: acting constraints a node is in
};

}  // namespace deformcd::response
