#include "cpu/cpu_bvh_trees.h"

#include <algorithm>
#include <string>

#include <glm/common.hpp>

#include "core/collision/bvh.h"
#include "cpu/parallel_for.h"
#include "deformcd/error.h"

namespace deformcd::cpu {

namespace {

// Box [lo, hi] of the node whose slot is `slot` (record * 2 + child) into its parent's record.
inline void write_slot(ChildBoxes* records, std::uint32_t slot, const glm::vec3& lo,
                       const glm::vec3& hi) {
  set_child_box(records[slot >> 1], slot & 1u, lo, hi);
}

}  // namespace

void BvhTrees::upload(const collision::CollisionData& data, collision::VertexPositions pose) {
  upkeep_.reset(data, pose);
  faces_ = data.faces;
  refit_nodes_.resize(upkeep_.nodes().size());
  make_refit_nodes(0, static_cast<std::uint32_t>(refit_nodes_.size()));
  boxes_.assign(upkeep_.nodes().size(), gpu::Box{});
  ratios_.assign(upkeep_.trees().size(), 0.0);
  make_child_boxes();
  cut_trees();
  refit(pose);
}

void BvhTrees::cut_trees() {
  pieces_.clear();
  top_nodes_.clear();
  piece_offset_.assign(1, 0u);
  top_offset_.assign(1, 0u);
  for (const gpu::BodyBvh& t : upkeep_.trees()) {
    const collision::BvhCut cut = collision::cut_bvh(upkeep_.nodes(), t.root, t.node_count);
    for (const glm::uvec2& s : cut.subtrees)
      pieces_.push_back({s.x, s.y});
    top_nodes_.insert(top_nodes_.end(), cut.top.begin(), cut.top.end());
    piece_offset_.push_back(static_cast<std::uint32_t>(pieces_.size()));
    top_offset_.push_back(static_cast<std::uint32_t>(top_nodes_.size()));
  }
  piece_areas_.assign(pieces_.size(), 0.0);
}

void make_child_records(const std::vector<gpu::BvhNode>& nodes, std::size_t face_count,
                        std::vector<ChildBoxes>& records, std::vector<std::uint32_t>& record_of,
                        std::vector<std::uint32_t>* slot_of) {
  if (face_count >= kLeafChild) {
    throw Error("CPU bvh: " + std::to_string(face_count) +
                " faces; the traversal's records hold fewer than 2^31");
  }
  record_of.assign(nodes.size(), gpu::kBvhInternal);
  std::uint32_t count = 0;
  for (std::uint32_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].face == gpu::kBvhInternal) record_of[i] = count++;
  }
  records.assign(count, ChildBoxes{});
  if (slot_of != nullptr) slot_of->assign(nodes.size(), gpu::kBvhInternal);
  for (std::uint32_t i = 0; i < nodes.size(); ++i) {
    const gpu::BvhNode& n = nodes[i];
    if (n.face != gpu::kBvhInternal) continue;
    const std::uint32_t children[2] = {n.left, n.right};
    for (std::uint32_t k = 0; k < 2; ++k) {
      const std::uint32_t c = children[k];
      records[record_of[i]].child[k] =
          nodes[c].face != gpu::kBvhInternal ? kLeafChild | nodes[c].face : record_of[c];
      if (slot_of != nullptr) (*slot_of)[c] = 2 * record_of[i] + k;
    }
  }
}

void BvhTrees::make_child_boxes() {
  const std::vector<gpu::BvhNode>& nodes = upkeep_.nodes();
  make_child_records(nodes, faces_.size(), child_boxes_, record_of_, &slots_);
  for (std::uint32_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].face == gpu::kBvhInternal) refit_nodes_[i].z = record_of_[i];
    if (slots_[i] != gpu::kBvhInternal) {
      write_slot(child_boxes_.data(), slots_[i], glm::vec3(boxes_[i].min),
                 glm::vec3(boxes_[i].max));
    }
  }
}

void BvhTrees::refit(collision::VertexPositions positions) {
  // One piece per task: every piece is 1 to kBvhCutNodes nodes, most of them over half that.
  parallel_for(
      pieces_.size(),
      [&](std::size_t p) {
        piece_areas_[p] = refit_range(pieces_[p].first, pieces_[p].count, positions);
      },
      1);
  for (std::uint32_t mesh = 0; mesh < ratios_.size(); ++mesh)
    refit_top(mesh);
}

void BvhTrees::make_refit_nodes(std::uint32_t first, std::uint32_t count) {
  const std::vector<gpu::BvhNode>& nodes = upkeep_.nodes();
  for (std::uint32_t i = first; i < first + count; ++i) {
    const gpu::BvhNode& n = nodes[i];
    if (n.face == gpu::kBvhInternal) {
      refit_nodes_[i] = {n.left, n.right, 0u, gpu::kBvhInternal};
    } else {
      const gpu::Face& f = faces_[n.face];
      refit_nodes_[i] = {f.a, f.b, f.c, f.body};
    }
  }
}

// The loop of collision::refit_bvh (reverse preorder, children first), reading refit_nodes_.
double BvhTrees::refit_range(std::uint32_t first, std::uint32_t count,
                             collision::VertexPositions positions) {
  double area = 0.0;
  for (std::uint32_t i = first + count; i-- > first;) {
    const RefitNode& n = refit_nodes_[i];
    // collision::refit_bvh's operations, in its order (a leaf grows the empty box by its
    // corners a, b, c), kept in registers: the box is stored, not built in memory and read back.
    glm::vec3 lo;
    glm::vec3 hi;
    if (n.mesh != gpu::kBvhInternal) {
      const gpu::Box e = collision::empty_box();
      lo = glm::vec3(e.min);
      hi = glm::vec3(e.max);
      for (const std::uint32_t v : {n.x, n.y, n.z}) {
        const glm::vec3 p = collision::vertex_position(positions, n.mesh, v);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
      }
    } else {
      // The children's boxes from the node's own record (one cache line, written by the
      // children just before), the same floats as boxes_[n.x] and boxes_[n.y].
      const ChildBoxes& r = child_boxes_[n.z];
      lo = glm::min(glm::vec3(r.min[0][0], r.min[1][0], r.min[2][0]),
                    glm::vec3(r.min[0][1], r.min[1][1], r.min[2][1]));
      hi = glm::max(glm::vec3(r.max[0][0], r.max[1][0], r.max[2][0]),
                    glm::vec3(r.max[0][1], r.max[1][1], r.max[2][1]));
    }
    const gpu::Box b = {glm::vec4(lo, 0.0f), glm::vec4(hi, 0.0f)};
    if (n.mesh == gpu::kBvhInternal) area += collision::box_area(b);
    boxes_[i] = b;
    if (slots_[i] != gpu::kBvhInternal) write_slot(child_boxes_.data(), slots_[i], lo, hi);
  }
  return area;
}

// The sum of collision::bvh_area_ratio: the pieces' sums in the cut's order, then the top
// nodes, last to first (children before parents, which the refit needs too).
void BvhTrees::refit_top(std::uint32_t mesh) {
  double internal = 0.0;
  for (std::uint32_t p = piece_offset_[mesh]; p < piece_offset_[mesh + 1]; ++p)
    internal += piece_areas_[p];
  for (std::uint32_t k = top_offset_[mesh + 1]; k-- > top_offset_[mesh];) {
    const std::uint32_t node = top_nodes_[k];
    const RefitNode& n = refit_nodes_[node];
    const gpu::Box& l = boxes_[n.x];
    const gpu::Box& r = boxes_[n.y];
    const gpu::Box b = {glm::vec4(glm::min(glm::vec3(l.min), glm::vec3(r.min)), 0.0f),
                        glm::vec4(glm::max(glm::vec3(l.max), glm::vec3(r.max)), 0.0f)};
    boxes_[node] = b;
    if (slots_[node] != gpu::kBvhInternal) {
      write_slot(child_boxes_.data(), slots_[node], glm::vec3(b.min), glm::vec3(b.max));
    }
    internal += collision::box_area(b);
  }
  const double root = collision::box_area(boxes_[upkeep_.tree(mesh).root]);
  ratios_[mesh] = root > 0.0 ? internal / root : 0.0;
}

std::uint32_t BvhTrees::rebuild_degraded(const std::vector<std::uint8_t>& traversed,
                                         collision::VertexPositions positions) {
  std::uint32_t rebuilt = 0;
  for (std::uint32_t mesh = 0; mesh < traversed.size(); ++mesh) {
    if (traversed[mesh] == 0u || !upkeep_.degraded(mesh, ratios_[mesh])) continue;
    upkeep_.rebuild(mesh, positions, boxes_);
    make_refit_nodes(upkeep_.tree(mesh).root, upkeep_.tree(mesh).node_count);
    ratios_[mesh] = upkeep_.built_ratio(mesh);
    ++rebuilt;
  }
  // A new topology, a new cut and new records.
  if (rebuilt > 0) {
    make_child_boxes();
    cut_trees();
  }
  return rebuilt;
}

}  // namespace deformcd::cpu
