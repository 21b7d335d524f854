#pragma once
// Binding points and layout of GlCollision's private work buffers: no C++ struct reads them and
// the CPU backend has none, so they are not in gpu::Binding. Mirrored by
// shaders/collision/gl_work_buffers.glsl (tests/gl/layout_agreement_test.cpp checks). No GL here.

#include <cstdint>

namespace deformcd::gl {

inline constexpr std::uint32_t kDispatchArgsBinding = 29;   // uint[12]: indirect args, a count
inline constexpr std::uint32_t kBoxPairListBinding = 30;    // uvec2 per listed leaf-box pair
inline constexpr std::uint32_t kBvhLevelsBinding = 31;      // uint per internal BVH node
inline constexpr std::uint32_t kTouchingPairsBinding = 32;  // uvec2 per touching body pair
inline constexpr std::uint32_t kBvhLeavesBinding = 33;      // uint per face: leaves in preorder
inline constexpr std::uint32_t kNonFiniteBinding = 34;      // uint per mesh: first bad vertex

// The dispatch-args buffer's size in uints, and its words (DISPATCH_ARGS_*): the argument
// triples of octree_candidates.comp, tri_tri_candidates.comp and bvh_traverse.comp, and the
// count of body pairs whose root boxes overlap.
inline constexpr std::uint32_t kDispatchArgsWords = 12;
inline constexpr std::uint32_t kExpandArgsWord = 0;
inline constexpr std::uint32_t kTouchingCountWord = 3;
inline constexpr std::uint32_t kNarrowArgsWord = 4;
inline constexpr std::uint32_t kTraverseArgsWord = 8;

}  // namespace deformcd::gl
