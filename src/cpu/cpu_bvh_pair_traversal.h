#pragma once
// Two BVHs descended together (the simultaneous traversal of FCL's `collide` and Bullet's
// `collideTT`): a stack of node pairs whose boxes overlap. Two internal nodes are split together
// into their four pairs of children (measured 2-6 % faster than splitting the node with the
// larger box, FCL's rule); once one node is a leaf, its box queries the other subtree. A pair of
// far-apart subtrees is rejected by one box test, where a query per face of one mesh into the
// other's tree rejects the same region once per query face (47 % of a one-thread bvh pass
// before, 35 % now with the triangle tests cheaper; see docs/benchmarks.md).
//
// Every leaf pair whose boxes overlap is visited exactly once, as with one query per face: a
// pair is split into children pairs that partition its leaf pairs, and a child pair is dropped
// only when its boxes are apart, which its leaves' boxes (inside them) then are too. A tree
// against itself visits each unordered pair of different leaves once: a node against itself
// splits into (left, left), (right, right) and (left, right).
//
// The work is cut into independent node pairs first (expand_frontier), which threads then
// traverse one each: results are appended per thread and sorted by the caller, so they do not
// depend on the thread count.

#include <cstdint>
#include <vector>

#include "core/collision/broad_phase.h"
#include "core/collision/bvh.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::cpu {

/// Two nodes to descend together; `a` in the first tree, `b` in the second (the same tree for a
/// mesh against itself, where a == b is the node against itself).
struct NodePair {
  std::uint32_t a;
  std::uint32_t b;
};

/// The stack a traversal needs: each step goes one level deeper in both trees and leaves at most
/// three pairs on the stack, so it never holds more than three per level of the shallower tree.
inline constexpr std::uint32_t kPairStackSize = 3 * collision::kBvhMaxDepth + 4;

namespace detail {

[[nodiscard]] inline bool is_leaf(const gpu::BvhNode& n) {
  return n.face != gpu::kBvhInternal;
}

// Splits pair p (not two leaves) and calls push(child pair) for each child pair whose boxes
// overlap. `self`: both nodes are in one tree, and p.a == p.b is a node against itself.
template <class Push>
void split_pair(const gpu::BvhNode* nodes, const gpu::Box* boxes, bool self, const NodePair& p,
                const Push& push) {
  const gpu::BvhNode& na = nodes[p.a];
  const gpu::BvhNode& nb = nodes[p.b];
  if (self && p.a == p.b) {  // internal, or the caller would not split it
    push({na.left, na.left});
    push({na.right, na.right});
    if (collision::boxes_overlap(boxes[na.left], boxes[na.right])) push({na.left, na.right});
    return;
  }
  // A leaf against an internal node: the internal one's children; two internal nodes: the four
  // pairs of children, as the traversal splits them.
  const bool split_a = !is_leaf(na);
  const bool split_b = !is_leaf(nb);
  for (int i = 0; i < (split_a ? 2 : 1); ++i) {
    const std::uint32_t a = split_a ? (i == 0 ? na.left : na.right) : p.a;
    for (int j = 0; j < (split_b ? 2 : 1); ++j) {
      const std::uint32_t b = split_b ? (j == 0 ? nb.left : nb.right) : p.b;
      if (collision::boxes_overlap(boxes[a], boxes[b])) push({a, b});
    }
  }
}

}  // namespace detail

/// Calls visit(face of the first tree, face of the second) for every pair of leaves under `start`
/// (whose boxes must overlap) whose boxes overlap. In a tree against itself (`self`), each
/// unordered pair of different leaves once, in either order.
///
/// The loop carries one pair and pushes only the other child pairs that overlap; once either
/// node is a leaf, the rest is a plain query of its box in the other subtree (query_bvh).
template <class Visit>
void traverse_node_pair(const gpu::BvhNode* nodes, const gpu::Box* boxes, bool self,
                        const NodePair& start, const Visit& visit) {
  NodePair stack[kPairStackSize];
  std::uint32_t size = 0;
  NodePair p = start;
  for (;;) {
    const gpu::BvhNode& na = nodes[p.a];
    const gpu::BvhNode& nb = nodes[p.b];
    const bool leaf_a = detail::is_leaf(na);
    const bool leaf_b = detail::is_leaf(nb);
    bool next = false;  // p holds the next pair to descend
    if (leaf_a && leaf_b) {
      if (!(self && p.a == p.b)) visit(na.face, nb.face);
    } else if (leaf_a) {
      collision::query_bvh(nodes, boxes, p.b, boxes[p.a],
                           [&](std::uint32_t face) { visit(na.face, face); });
    } else if (leaf_b) {
      collision::query_bvh(nodes, boxes, p.a, boxes[p.b],
                           [&](std::uint32_t face) { visit(face, nb.face); });
    } else if (self && p.a == p.b) {
      if (collision::boxes_overlap(boxes[na.left], boxes[na.right])) {
        stack[size++] = {na.left, na.right};
      }
      stack[size++] = {na.right, na.right};
      p = {na.left, na.left};
      next = true;
    } else {
      // Both internal: the four pairs of children; the first that overlaps is descended next.
      const gpu::Box& al = boxes[na.left];
      const gpu::Box& ar = boxes[na.right];
      const gpu::Box& bl = boxes[nb.left];
      const gpu::Box& br = boxes[nb.right];
      if (collision::boxes_overlap(ar, br)) stack[size++] = {na.right, nb.right};
      if (collision::boxes_overlap(ar, bl)) stack[size++] = {na.right, nb.left};
      if (collision::boxes_overlap(al, br)) stack[size++] = {na.left, nb.right};
      if (collision::boxes_overlap(al, bl)) {
        p = {na.left, nb.left};
        next = true;
      }
    }
    if (next) continue;
    if (size == 0) return;
    p = stack[--size];
  }
}

/// Replaces `pairs` (node pairs with overlapping boxes) by their children pairs, level by level,
/// until there are at least `target` of them or only leaf pairs are left: independent pieces of
/// one traversal, whose leaf pairs together are those of the pairs given.
inline void expand_frontier(const gpu::BvhNode* nodes, const gpu::Box* boxes, bool self,
                            std::size_t target, std::vector<NodePair>& pairs,
                            std::vector<NodePair>& scratch) {
  while (pairs.size() < target) {
    scratch.clear();
    bool split = false;
    for (const NodePair& p : pairs) {
      if (detail::is_leaf(nodes[p.a]) && detail::is_leaf(nodes[p.b])) {
        scratch.push_back(p);
        continue;
      }
      split = true;
      detail::split_pair(nodes, boxes, self, p, [&](const NodePair& c) { scratch.push_back(c); });
    }
    pairs.swap(scratch);
    if (!split) return;
  }
}

}  // namespace deformcd::cpu
