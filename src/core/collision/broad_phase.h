#pragma once
// The per-element steps of the broad phases, as pure functions: the CPU backend calls them and
// shaders/collision/broad_phase.glsl mirrors them line for line, so both backends make the same
// decisions on the same floats.

#include <bit>
#include <cstdint>
#include <limits>

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "deformcd/gpu_layout.h"

namespace deformcd::collision {

/// A box that contains nothing and overlaps nothing (a leaf box that lists no face).
[[nodiscard]] inline gpu::Box empty_box() {
  const float big = std::numeric_limits<float>::max();
  return {glm::vec4(big, big, big, 0.0f), glm::vec4(-big, -big, -big, 0.0f)};
}

inline void grow_box(gpu::Box& box, const glm::vec3& p) {
  box.min = glm::vec4(glm::min(glm::vec3(box.min), p), 0.0f);
  box.max = glm::vec4(glm::max(glm::vec3(box.max), p), 0.0f);
}

/// Closed boxes: touching counts as overlapping, since touching triangles intersect.
[[nodiscard]] inline bool boxes_overlap(const gpu::Box& a, const gpu::Box& b) {
  // Bitwise: all six comparisons and no branch between them. The searches' box tests pass
  // about half the time, where each branch of a short-circuit chain was mispredicted as often.
  return static_cast<bool>(
      static_cast<int>(a.min.x <= b.max.x) & static_cast<int>(b.min.x <= a.max.x) &
      static_cast<int>(a.min.y <= b.max.y) & static_cast<int>(b.min.y <= a.max.y) &
      static_cast<int>(a.min.z <= b.max.z) & static_cast<int>(b.min.z <= a.max.z));
}

/// Whether bit `box` (0-63) of a face's leaf-box set is set.
[[nodiscard]] inline bool has_box(const glm::uvec2& boxes, std::uint32_t box) {
  return ((boxes[box / 32u] >> (box % 32u)) & 1u) != 0u;
}

/// A face pair listed under several box pairs must be tested and reported once: only from the
/// first box pair (box_a, box_b), in lexicographic order, among the pairs listing both faces
/// whose boxes overlap. `overlap(i, j)` reads the body pair's box mask. The loops run over the
/// faces' few boxes (usually one or two each), and only for face pairs that passed the mask.
template <class Overlap>
[[nodiscard]] bool is_first_box_pair(const glm::uvec2& boxes_a, const glm::uvec2& boxes_b,
                                     std::uint32_t box_a, std::uint32_t box_b,
                                     const Overlap& overlap) {
  for (std::uint32_t wa = 0; wa < 2u; ++wa) {
    std::uint32_t bits_a = boxes_a[wa];
    while (bits_a != 0u) {
      const std::uint32_t i = 32u * wa + static_cast<std::uint32_t>(std::countr_zero(bits_a));
      bits_a &= bits_a - 1u;
      if (i > box_a) return true;
      for (std::uint32_t wb = 0; wb < 2u; ++wb) {
        std::uint32_t bits_b = boxes_b[wb];
        while (bits_b != 0u) {
          const std::uint32_t j = 32u * wb + static_cast<std::uint32_t>(std::countr_zero(bits_b));
          bits_b &= bits_b - 1u;
          if ((i < box_a || j < box_b) && overlap(i, j)) return false;
        }
      }
    }
  }
  return true;
}

}  // namespace deformcd::collision
