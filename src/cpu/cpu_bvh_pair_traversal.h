#pragma once
// Two BVHs descended together (the simultaneous traversal of FCL's `collide` and Bullet's
// `collideTT`): a stack of node pairs whose boxes overlap. Two internal nodes are split together
// into their four pairs of children (measured 2-6 % faster than splitting the node with the
// larger box, FCL's rule); once one node is a leaf, its box queries the other subtree. A pair of
// far-apart subtrees is rejected by one box test, where a query per face of one mesh into the
// other's tree rejects the same region once per query face (47 % of a one-thread bvh pass
// before, 35 % then with the triangle tests cheaper; see docs/benchmarks.md). Below the start,
// the descent reads BvhTrees' records of the children's boxes (ChildBoxes), four child pairs
// per pair of records in SSE lanes: 21 % of a one-thread pass on phase 1 since (2026-12-02).
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

#include <bit>
#include <cstdint>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/collision/broad_phase.h"
#include "core/collision/bvh.h"
#include "cpu/cpu_bvh_trees.h"
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

/// The trees as the traversal reads them: the nodes and boxes (of every node), and the records
/// of the internal nodes' children (BvhTrees::child_boxes, record_of).
struct TraversalTrees {
  const gpu::BvhNode* nodes;
  const gpu::Box* boxes;
  const ChildBoxes* records;
  const std::uint32_t* record_of;
};

namespace detail {

// A closed box as three mins and three maxes.
struct Box3 {
  float min[3];
  float max[3];
};

[[nodiscard]] inline Box3 child_box(const ChildBoxes& r, int k) {
  return {{r.min[0][k], r.min[1][k], r.min[2][k]}, {r.max[0][k], r.max[1][k], r.max[2][k]}};
}

// collision::boxes_overlap of child i of x and child j of y, evaluated without branches (each
// comparison as boxes_overlap makes it, so the same answer, NaN included).
[[nodiscard]] inline unsigned children_overlap(const ChildBoxes& x, int i, const ChildBoxes& y,
                                               int j) {
  return static_cast<unsigned>(x.min[0][i] <= y.max[0][j]) &
         static_cast<unsigned>(y.min[0][j] <= x.max[0][i]) &
         static_cast<unsigned>(x.min[1][i] <= y.max[1][j]) &
         static_cast<unsigned>(y.min[1][j] <= x.max[1][i]) &
         static_cast<unsigned>(x.min[2][i] <= y.max[2][j]) &
         static_cast<unsigned>(y.min[2][j] <= x.max[2][i]);
}

// The four pairs of children of x and y: bit 2i + j is children_overlap(x, i, y, j). With SSE,
// the four pairs in the four lanes (the same comparisons: cmpleps is <= and false on NaN);
// a third of the one-thread traversal's time went to these 24 scalar comparisons.
[[nodiscard]] inline unsigned four_children_overlap(const ChildBoxes& x, const ChildBoxes& y) {
#if defined(__SSE2__)
  // min[0..1][*] and max[0..1][*] as (axis 0 child 0, axis 0 child 1, axis 1 child 0, axis 1
  // child 1); axis 2 in the low half of a second load.
  const __m128 x_min01 = _mm_loadu_ps(&x.min[0][0]);
  const __m128 x_max01 = _mm_loadu_ps(&x.max[0][0]);
  const __m128 y_min01 = _mm_loadu_ps(&y.min[0][0]);
  const __m128 y_max01 = _mm_loadu_ps(&y.max[0][0]);
  const __m128 x_min2 = _mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(&x.min[2][0])));
  const __m128 x_max2 = _mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(&x.max[2][0])));
  const __m128 y_min2 = _mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(&y.min[2][0])));
  const __m128 y_max2 = _mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(&y.max[2][0])));
  // Lane 2i + j: x's child i (0, 0, 1, 1) against y's child j (0, 1, 0, 1).
  const auto xs = [](__m128 v, int axis) {
    return axis == 0 ? _mm_shuffle_ps(v, v, _MM_SHUFFLE(1, 1, 0, 0))
                     : _mm_shuffle_ps(v, v, _MM_SHUFFLE(3, 3, 2, 2));
  };
  const auto ys = [](__m128 v, int axis) {
    return axis == 0 ? _mm_shuffle_ps(v, v, _MM_SHUFFLE(1, 0, 1, 0))
                     : _mm_shuffle_ps(v, v, _MM_SHUFFLE(3, 2, 3, 2));
  };
  __m128 m = _mm_and_ps(_mm_cmple_ps(xs(x_min01, 0), ys(y_max01, 0)),
                        _mm_cmple_ps(ys(y_min01, 0), xs(x_max01, 0)));
  m = _mm_and_ps(m, _mm_cmple_ps(xs(x_min01, 1), ys(y_max01, 1)));
  m = _mm_and_ps(m, _mm_cmple_ps(ys(y_min01, 1), xs(x_max01, 1)));
  m = _mm_and_ps(m, _mm_cmple_ps(xs(x_min2, 0), ys(y_max2, 0)));
  m = _mm_and_ps(m, _mm_cmple_ps(ys(y_min2, 0), xs(x_max2, 0)));
  return static_cast<unsigned>(_mm_movemask_ps(m));
#else
  return children_overlap(x, 0, y, 0) | children_overlap(x, 0, y, 1) << 1u |
         children_overlap(x, 1, y, 0) << 2u | children_overlap(x, 1, y, 1) << 3u;
#endif
}

// Bit k: child k of x overlaps box q (boxes_overlap's comparisons, without branches).
[[nodiscard]] inline unsigned children_overlap_box(const ChildBoxes& x, const Box3& q) {
  unsigned hits = 0;
  for (int k = 0; k < 2; ++k) {
    const unsigned hit = static_cast<unsigned>(x.min[0][k] <= q.max[0]) &
                         static_cast<unsigned>(q.min[0] <= x.max[0][k]) &
                         static_cast<unsigned>(x.min[1][k] <= q.max[1]) &
                         static_cast<unsigned>(q.min[1] <= x.max[1][k]) &
                         static_cast<unsigned>(x.min[2][k] <= q.max[2]) &
                         static_cast<unsigned>(q.min[2] <= x.max[2][k]);
    hits |= hit << k;
  }
  return hits;
}

// Calls visit(face) for every leaf under the internal node of record `root` whose box overlaps
// q (collision::query_bvh over the records: both children's boxes are tested from one load).
template <class Visit>
void query_records(const ChildBoxes* records, std::uint32_t root, const Box3& q,
                   const Visit& visit) {
  std::uint32_t stack[collision::kBvhMaxDepth + 1];
  std::uint32_t size = 0;
  std::uint32_t x = root;
  for (;;) {
    const ChildBoxes& r = records[x];
    const unsigned hits = children_overlap_box(r, q);
    const unsigned hit0 = hits & 1u;
    const unsigned hit1 = hits & 2u;
    bool next = false;
    if (hit1 != 0u) {
      if ((r.child[1] & kLeafChild) != 0u) {
        visit(r.child[1] & ~kLeafChild);
      } else {
        x = r.child[1];
        next = true;
      }
    }
    if (hit0 != 0u) {
      if ((r.child[0] & kLeafChild) != 0u) {
        visit(r.child[0] & ~kLeafChild);
      } else {
        if (next) stack[size++] = x;
        x = r.child[0];
        next = true;
      }
    }
    if (next) continue;
    if (size == 0) return;
    x = stack[--size];
  }
}

}  // namespace detail

/// Calls visit(face of the first tree, face of the second) for every pair of leaves under `start`
/// (whose boxes must overlap) whose boxes overlap. In a tree against itself (`self`), each
/// unordered pair of different leaves once, in either order.
///
/// Over the records of the internal nodes (ChildBoxes): a pair of internal nodes tests its four
/// pairs of children from the two records and keeps those that overlap; a pair of internal
/// children goes on the stack, a leaf against an internal child queries that child's subtree
/// with the leaf's box, two leaves are visited.
template <class Visit>
void traverse_node_pair(const TraversalTrees& t, bool self, const NodePair& start,
                        const Visit& visit) {
  const gpu::BvhNode& na = t.nodes[start.a];
  const gpu::BvhNode& nb = t.nodes[start.b];
  const bool leaf_a = detail::is_leaf(na);
  const bool leaf_b = detail::is_leaf(nb);
  const auto box3 = [](const gpu::Box& b) {
    return detail::Box3{{b.min.x, b.min.y, b.min.z}, {b.max.x, b.max.y, b.max.z}};
  };
  if (leaf_a && leaf_b) {
    if (!(self && start.a == start.b)) visit(na.face, nb.face);
    return;
  }
  if (leaf_a) {
    detail::query_records(t.records, t.record_of[start.b], box3(t.boxes[start.a]),
                          [&](std::uint32_t face) { visit(na.face, face); });
    return;
  }
  if (leaf_b) {
    detail::query_records(t.records, t.record_of[start.a], box3(t.boxes[start.b]),
                          [&](std::uint32_t face) { visit(face, nb.face); });
    return;
  }
  // Pairs of records: a == b (in a tree against itself) is a node against itself.
  NodePair stack[kPairStackSize];
  std::uint32_t size = 0;
  NodePair p{t.record_of[start.a], t.record_of[start.b]};
  for (;;) {
    const ChildBoxes& x = t.records[p.a];
    const ChildBoxes& y = t.records[p.b];
    // Bit 2i + j: child i of x and child j of y overlap. A node against itself: its children
    // against themselves go on the stack (internal ones; a leaf meets no other leaf there), and
    // child 0 against child 1 (bit 1) is a pair like the others.
    unsigned hits = 0;
    if (self && p.a == p.b) {
      for (int k = 0; k < 2; ++k) {
        if ((x.child[k] & kLeafChild) == 0u) stack[size++] = {x.child[k], x.child[k]};
      }
      hits = detail::children_overlap(x, 0, x, 1) << 1u;
    } else {
      hits = detail::four_children_overlap(x, y);
    }
    while (hits != 0u) {
      const int i = std::countr_zero(hits) >> 1;
      const int j = std::countr_zero(hits) & 1;
      hits &= hits - 1u;
      const std::uint32_t cx = x.child[i];
      const std::uint32_t cy = y.child[j];
      const bool lx = (cx & kLeafChild) != 0u;
      const bool ly = (cy & kLeafChild) != 0u;
      if (lx && ly) {
        visit(cx & ~kLeafChild, cy & ~kLeafChild);
      } else if (lx) {
        detail::query_records(t.records, cy, detail::child_box(x, i),
                              [&](std::uint32_t face) { visit(cx & ~kLeafChild, face); });
      } else if (ly) {
        detail::query_records(t.records, cx, detail::child_box(y, j),
                              [&](std::uint32_t face) { visit(face, cy & ~kLeafChild); });
      } else {
        // The records are read when the pair is popped: start loading them now (the records
        // of a 5,000-face body, 300 KB, stay in L2, not L1).
        __builtin_prefetch(&t.records[cx]);
        __builtin_prefetch(&t.records[cy]);
        stack[size++] = {cx, cy};
      }
    }
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
