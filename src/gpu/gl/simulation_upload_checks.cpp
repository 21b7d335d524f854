#include "gpu/gl/simulation_upload_checks.h"

#include <string>

#include "deformcd/error.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::gl {

namespace {

template <class T>
BufferSize size_of(std::string_view name, gpu::Binding binding, const std::vector<T>& data) {
  return {name, binding, data.size(), sizeof(T)};
}

[[noreturn]] void inconsistent(const std::string& what) {
  throw Error("SimulationState is inconsistent: " + what);
}

void expect_length(std::string_view array, std::size_t length, std::string_view reference,
                   std::size_t expected) {
  if (length != expected) {
    inconsistent(std::string(array) + " has " + std::to_string(length) + " entries, but " +
                 std::string(reference) + " calls for " + std::to_string(expected));
  }
}

void check_springs(const SimulationState& w) {
  for (std::size_t s = 0; s < w.springs.size(); ++s) {
    const gpu::Spring& spring = w.springs[s];
    if (spring.a >= w.node_count() || spring.b >= w.node_count()) {
      inconsistent("spring " + std::to_string(s) + " joins nodes " + std::to_string(spring.a) +
                   " and " + std::to_string(spring.b) + ", but there are " +
                   std::to_string(w.node_count()) + " nodes");
    }
  }
}

// A per-node CSR list: offsets start at 0, never decrease, and end at the list's length.
void check_csr_offsets(const std::string& name, const std::vector<std::uint32_t>& offset,
                       std::size_t list_length) {
  if (offset.front() != 0) inconsistent(name + "_offset[0] is not 0");
  for (std::size_t i = 0; i + 1 < offset.size(); ++i) {
    if (offset[i + 1] < offset[i]) {
      inconsistent(name + "_offset decreases at node " + std::to_string(i));
    }
  }
  expect_length(name + "_list", list_length, name + "_offset's last entry", offset.back());
}

void check_node_springs(const SimulationState& w) {
  check_csr_offsets("node_spring", w.node_spring_offset, w.node_spring_list.size());
  for (std::size_t e = 0; e < w.node_spring_list.size(); ++e) {
    // 64 bits: negating INT32_MIN would overflow.
    const std::int64_t tag = w.node_spring_list[e];
    const std::int64_t spring = (tag > 0 ? tag : -tag) - 1;
    if (spring < 0 || static_cast<std::uint64_t>(spring) >= w.springs.size()) {
      inconsistent("node_spring_list[" + std::to_string(e) + "] = " + std::to_string(tag) +
                   " names no spring (there are " + std::to_string(w.springs.size()) + ")");
    }
  }
}

void check_tets(const SimulationState& w) {
  for (std::size_t t = 0; t < w.tets.size(); ++t) {
    const gpu::Tetra& tet = w.tets[t];
    for (std::uint32_t n : {tet.a, tet.b, tet.c, tet.d}) {
      if (n >= w.node_count()) {
        inconsistent("tetrahedron " + std::to_string(t) + " has node " + std::to_string(n) +
                     ", but there are " + std::to_string(w.node_count()) + " nodes");
      }
    }
  }
  check_csr_offsets("node_tet", w.node_tet_offset, w.node_tet_list.size());
  for (std::size_t e = 0; e < w.node_tet_list.size(); ++e) {
    if (w.node_tet_list[e] >= w.tet_forces.size()) {
      inconsistent("node_tet_list[" + std::to_string(e) +
                   "] = " + std::to_string(w.node_tet_list[e]) + " names no tetrahedron corner");
    }
  }
}

}  // namespace

std::vector<BufferSize> simulation_buffer_sizes(const SimulationState& w,
                                                const sim::SpringEdges& edges,
                                                const sim::TetCorners& corners) {
  return {
      size_of("Node Position", gpu::kNodePosition, w.positions),
      size_of("Node Velocity", gpu::kNodeVelocity, w.velocities),
      {"Spring Edge", gpu::kSpringEdge, edges.size(), sizeof(gpu::SpringEdge)},
      size_of("Node Force", gpu::kNodeForce, w.forces),
      size_of("Body Parameters", gpu::kBodyParams, w.body_params),
      size_of("Node Body", gpu::kNodeBody, w.node_body),
      {"Edge State", gpu::kEdgeState, edges.size(), sizeof(glm::vec4)},
      size_of("Node Edge Offset", gpu::kNodeEdgeOffset, edges.node_offset),
      size_of("Node Edge Term", gpu::kNodeEdgeTerm, edges.node_terms),
      size_of("Tetrahedron Information", gpu::kTetInfo, corners.tets),
      {"Corner Force", gpu::kCornerForce, corners.slot_count, sizeof(glm::vec4)},
      size_of("Node Corner Offset", gpu::kNodeCornerOffset, corners.node_offset),
      {"Tetrahedron Corner Slot", gpu::kTetCornerSlot, corners.tets.size(),
       4 * sizeof(std::uint32_t)},
  };
}

void check_buffer_sizes(std::span<const BufferSize> buffers, std::uint64_t max_bytes,
                        std::string_view limit_name, std::string_view owner) {
  std::string too_large;
  for (const BufferSize& b : buffers) {
    if (b.bytes() <= max_bytes) continue;
    too_large += "\n  " + std::string(b.name) + " (SSBO " + std::to_string(b.binding) +
                 "): " + std::to_string(b.bytes()) + " bytes (" + std::to_string(b.count) + " x " +
                 std::to_string(b.element_bytes) + ")";
  }
  if (!too_large.empty()) {
    throw GlError(std::string(owner) + ": buffers larger than " + std::string(limit_name) + " (" +
                  std::to_string(max_bytes) + " bytes):" + too_large);
  }
}

void check_world_consistency(const SimulationState& w) {
  const std::size_t nodes = w.node_count();
  expect_length("velocities", w.velocities.size(), "positions", nodes);
  expect_length("forces", w.forces.size(), "positions", nodes);
  expect_length("node_body", w.node_body.size(), "positions", nodes);
  expect_length("node_spring_offset", w.node_spring_offset.size(), "positions (+1)", nodes + 1);
  expect_length("spring_forces", w.spring_forces.size(), "springs", w.springs.size());
  for (std::size_t i = 0; i < nodes; ++i) {
    if (w.node_body[i] >= w.body_params.size()) {
      inconsistent("node " + std::to_string(i) + " belongs to body " +
                   std::to_string(w.node_body[i]) + ", but there are " +
                   std::to_string(w.body_params.size()) + " bodies");
    }
  }
  expect_length("node_tet_offset", w.node_tet_offset.size(), "positions (+1)", nodes + 1);
  expect_length("tet_forces", w.tet_forces.size(), "tets (x4)", 4 * w.tets.size());
  check_springs(w);
  check_node_springs(w);
  check_tets(w);
}

}  // namespace deformcd::gl
