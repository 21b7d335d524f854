#pragma once
// The order of a projection's Gauss-Seidel sweeps (contact_constraints.h): the acting
// constraints in colours, no two constraints of one colour sharing a node, so that a colour's
// constraints can be solved at once, in any order and on any number of threads (or GPU
// invocations), with the same result bit for bit. Colours are given first fit in the acting
// list's order (greedy colouring), the contacts apart from the volume constraints, which a sweep
// solves after them. Both response backends call this one function on the same acting list, so
// their sweeps are the same: the colours need no GPU colouring to agree.
//
// The nodes are split in two halves at the median of the acting constraints' first nodes along
// the longest side of their box (where the window started; along the axis whose smaller half
// holds the most constraints when that side's holds under a quarter): each colour of a group's
// (the contacts', the volume constraints') first run of colours lists the first half's
// constraints, then the second's, and the constraints with nodes in both halves take the
// group's last colours. So a CPU sweep can solve the two halves of a run on two threads, each
// through all the run's colours without waiting at each colour, and still give the bits of a
// sweep colour after colour (the GPU's): a constraint reads only nodes its own half writes.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "deformcd/gpu_layout.h"

namespace deformcd::response {

class SweepOrder {
 public:
  /// Consecutive colours whose places are split in halves (halves) or not.
  struct Run {
    std::uint32_t first = 0;  ///< the run's first colour
    std::uint32_t end = 0;    ///< one past its last
    bool halves = false;      ///< each colour's two halves share no node
  };

  /// Colours the acting constraints: acting[a] indexes `pairs`; the first `contacts` entries
  /// are contacts, the rest volume constraints. `positions` are the nodes' where the window
  /// started (the halves' split); every node is below positions.size().
  void colour(std::span<const gpu::ContactPair> pairs, std::span<const std::uint32_t> acting,
              std::uint32_t contacts, std::span<const glm::vec3> positions);

  /// Acting places (indices into the acting list), colour by colour (the contacts' colours
  /// first), each colour's in acting order within each half.
  [[nodiscard]] const std::vector<std::uint32_t>& order() const { return order_; }
  /// Colour c's places are order()[colour_begin()[c], colour_begin()[c + 1]); one more entry
  /// than there are colours.
  [[nodiscard]] const std::vector<std::uint32_t>& colour_begin() const { return colour_begin_; }
  /// Colour c's second half starts at order()[half_begin()[c]] (colour_begin()[c + 1] for a
  /// colour that is not split).
  [[nodiscard]] const std::vector<std::uint32_t>& half_begin() const { return half_begin_; }
  /// The colours in sweep order as runs: the contacts' halves, the contacts across them, the
  /// volume constraints' halves, those across them (empty runs left out).
  [[nodiscard]] const std::vector<Run>& runs() const { return runs_; }
  /// The first contact_colours() colours are the contacts'.
  [[nodiscard]] std::uint32_t contact_colours() const { return contact_colours_; }
  /// The half (0 or 1) of a node whose window-start position is `x`: a constraint is in a half
  /// when all its nodes are.
  [[nodiscard]] std::uint32_t half_of(const glm::vec3& x) const {
    return x[axis_] < split_ ? 0u : 1u;
  }

 private:
  // The median of the acting constraints' first nodes' coordinate `axis`.
  float median_split(std::span<const gpu::ContactPair> pairs, std::span<const std::uint32_t> acting,
                     std::span<const glm::vec3> positions, int axis);
  // How many acting constraints the smaller half holds when split at `split` along `axis`.
  [[nodiscard]] static std::uint32_t smaller_half(std::span<const gpu::ContactPair> pairs,
                                                  std::span<const std::uint32_t> acting,
                                                  std::span<const glm::vec3> positions, int axis,
                                                  float split);
  // A constraint's half when split at `split` along `axis` (half_of's rule for each node): 0 or
  // 1 when all its nodes are in that half, 2 when it is across.
  [[nodiscard]] static std::uint8_t constraint_half(const gpu::ContactPair& pair,
                                                    std::span<const glm::vec3> positions, int axis,
                                                    float split);
  // Splits acting[first, end) into halves_ (0, 1, or 2 for across) and colours it into colour_
  // from colour `base` on; returns the colours it used after base.
  std::uint32_t colour_group(std::span<const gpu::ContactPair> pairs,
                             std::span<const std::uint32_t> acting, std::uint32_t first,
                             std::uint32_t end, std::span<const glm::vec3> positions,
                             std::uint32_t base);
  // Colours the places `places` first fit from colour `base` on; returns the colours used.
  std::uint32_t first_fit(std::span<const gpu::ContactPair> pairs,
                          std::span<const std::uint32_t> acting,
                          std::span<const std::uint32_t> places, std::uint32_t base);

  std::vector<std::uint32_t> order_;
  std::vector<std::uint32_t> colour_begin_;
  std::vector<std::uint32_t> half_begin_;
  std::vector<Run> runs_;
  std::uint32_t contact_colours_ = 0;
  int axis_ = 0;                       // the halves' split: along this axis,
  float split_ = 0.0f;                 // below this coordinate the first half
  std::vector<std::uint32_t> colour_;  // per acting place
  std::vector<std::uint8_t> half_;     // per acting place: 0, 1, or 2 (across the halves)
  // Per node, the colours its constraints of the places being coloured took: words_ 64-bit
  // words a node; all zero between calls (each first_fit clears the nodes it set).
  std::vector<std::uint64_t> taken_;
  std::uint32_t words_ = 0;
  std::uint32_t node_count_ = 0;
  std::vector<std::uint32_t> per_node_;      // scratch: acting constraints a node is in (0 between)
  std::vector<std::uint32_t> bucket_start_;  // scratch: the counting sort's (colour, half) starts
  std::vector<std::uint32_t> places_;        // scratch: a group's places of one kind
  std::vector<float> keys_;                  // scratch: a group's split coordinates
};

}  // namespace deformcd::response
