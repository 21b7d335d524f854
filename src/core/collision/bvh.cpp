#include "core/collision/bvh.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include <glm/common.hpp>

#include "core/collision/broad_phase.h"
#include "deformcd/error.h"

namespace deformcd::collision {

namespace {

glm::vec3 centroid(VertexPositions p, const gpu::Face& f) {
  glm::vec3 v[3];
  face_vertices(p, f, v);
  return (v[0] + v[1] + v[2]) / 3.0f;
}

// A range of faces waiting to become the subtree rooted at `node`.
struct Pending {
  std::uint32_t node;
  std::uint32_t begin;
  std::uint32_t end;
};

}  // namespace

std::vector<gpu::BvhNode> build_bvh(VertexPositions positions, const std::vector<gpu::Face>& faces,
                                    std::uint32_t face_offset, std::uint32_t face_count,
                                    std::uint32_t node_offset) {
  if (face_count == 0) throw Error("a BVH needs at least one face");
  std::vector<std::uint32_t> order(face_count);
  std::iota(order.begin(), order.end(), face_offset);
  std::vector<glm::vec3> centroids(face_count);
  for (std::uint32_t i = 0; i < face_count; ++i) {
    centroids[i] = centroid(positions, faces[face_offset + i]);
  }
  const auto c = [&](std::uint32_t face) { return centroids[face - face_offset]; };

  std::vector<gpu::BvhNode> nodes;
  nodes.reserve(2 * std::size_t{face_count} - 1);
  nodes.push_back({gpu::kBvhInternal, gpu::kBvhInternal, gpu::kBvhInternal, gpu::kBvhInternal});
  // Depth first, left subtree before right, so that nodes come out in preorder.
  std::vector<Pending> stack = {{0, 0, face_count}};
  while (!stack.empty()) {
    const Pending p = stack.back();
    stack.pop_back();
    if (p.end - p.begin == 1) {
      nodes[p.node].face = order[p.begin];
      continue;
    }
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(std::numeric_limits<float>::lowest());
    for (std::uint32_t i = p.begin; i < p.end; ++i) {
      lo = glm::min(lo, c(order[i]));
      hi = glm::max(hi, c(order[i]));
    }
    const glm::vec3 extent = hi - lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                     : extent.y >= extent.z                       ? 1
                                                                  : 2;
    const std::uint32_t mid = p.begin + (p.end - p.begin) / 2;
    // Ties broken by face index: the same tree on every run and platform.
    std::nth_element(order.begin() + p.begin, order.begin() + mid, order.begin() + p.end,
                     [&](std::uint32_t x, std::uint32_t y) {
                       const float cx = c(x)[axis];
                       const float cy = c(y)[axis];
                       return cx < cy || (cx == cy && x < y);
                     });
    // The left child is the next node in preorder; the right one is placed after the whole
    // left subtree (2 x its faces - 1 nodes).
    const auto left = static_cast<std::uint32_t>(p.node + 1);
    const std::uint32_t right = left + 2 * (mid - p.begin) - 1;
    nodes.resize(std::max<std::size_t>(nodes.size(), right + 1),
                 {gpu::kBvhInternal, gpu::kBvhInternal, gpu::kBvhInternal, gpu::kBvhInternal});
    nodes[p.node].left = node_offset + left;
    nodes[p.node].right = node_offset + right;
    nodes[left].parent = node_offset + p.node;
    nodes[right].parent = node_offset + p.node;
    stack.push_back({right, mid, p.end});
    stack.push_back({left, p.begin, mid});
  }
  return nodes;
}

std::uint32_t bvh_depth(const std::vector<gpu::BvhNode>& nodes, std::uint32_t root) {
  // Preorder: a node's depth is its parent's + 1, and parents come first.
  const std::uint32_t offset = root;
  std::vector<std::uint32_t> depth(nodes.size(), 0);
  std::uint32_t deepest = 0;
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    depth[i] = depth[nodes[i].parent - offset] + 1;
    deepest = std::max(deepest, depth[i]);
  }
  return deepest;
}

BvhCut cut_bvh(const std::vector<gpu::BvhNode>& nodes, std::uint32_t first, std::uint32_t count,
               std::uint32_t max_nodes) {
  BvhCut cut;
  // Depth first, left before right: both lists come out in preorder.
  std::vector<glm::uvec2> stack = {{first, count}};
  while (!stack.empty()) {
    const glm::uvec2 s = stack.back();
    stack.pop_back();
    const gpu::BvhNode& n = nodes[s.x];
    if (s.y <= max_nodes || n.face != gpu::kBvhInternal) {
      cut.subtrees.push_back(s);
      continue;
    }
    cut.top.push_back(s.x);
    stack.emplace_back(n.right, s.x + s.y - n.right);
    stack.emplace_back(n.left, n.right - n.left);
  }
  return cut;
}

void refit_bvh(const std::vector<gpu::BvhNode>& nodes, std::uint32_t first, std::uint32_t count,
               VertexPositions positions, const std::vector<gpu::Face>& faces,
               std::vector<gpu::Box>& boxes) {
  for (std::uint32_t i = first + count; i-- > first;) {
    const gpu::BvhNode& n = nodes[i];
    gpu::Box b = empty_box();
    if (n.face != gpu::kBvhInternal) {
      const gpu::Face& f = faces[n.face];
      grow_box(b, vertex_position(positions, f.body, f.a));
      grow_box(b, vertex_position(positions, f.body, f.b));
      grow_box(b, vertex_position(positions, f.body, f.c));
    } else {
      const gpu::Box& l = boxes[n.left];
      const gpu::Box& r = boxes[n.right];
      b.min = glm::vec4(glm::min(glm::vec3(l.min), glm::vec3(r.min)), 0.0f);
      b.max = glm::vec4(glm::max(glm::vec3(l.max), glm::vec3(r.max)), 0.0f);
    }
    boxes[i] = b;
  }
}

double bvh_area_ratio(const std::vector<gpu::BvhNode>& nodes, std::uint32_t first,
                      std::uint32_t count, const std::vector<gpu::Box>& boxes) {
  const BvhCut cut = cut_bvh(nodes, first, count);
  double internal = 0.0;
  for (const glm::uvec2& s : cut.subtrees) {
    double sum = 0.0;
    for (std::uint32_t i = s.x + s.y; i-- > s.x;) {
      if (nodes[i].face == gpu::kBvhInternal) sum += box_area(boxes[i]);
    }
    internal += sum;
  }
  for (std::size_t k = cut.top.size(); k-- > 0;)
    internal += box_area(boxes[cut.top[k]]);
  const double root = box_area(boxes[first]);
  return root > 0.0 ? internal / root : 0.0;
}

}  // namespace deformcd::collision
