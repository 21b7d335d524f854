#include "core/sim/node_force_lists.h"

#include <algorithm>
#include <bit>
#include <string>
#include <tuple>

#include "deformcd/error.h"

namespace deformcd::sim {

namespace {

void check(bool condition, const std::string& what) {
  if (!condition) throw Error("simulation state: " + what);
}

void check_offsets(const std::vector<std::uint32_t>& offset, std::size_t nodes,
                   std::size_t list_size, const char* name) {
  check(offset.size() == nodes + 1,
        std::string(name) + " has " + std::to_string(offset.size()) + " entries, not nodes + 1");
  check(offset.front() == 0 && offset.back() == list_size,
        std::string(name) + " does not span its list");
  check(std::is_sorted(offset.begin(), offset.end()), std::string(name) + " is not ascending");
}

}  // namespace

SpringEdges build_spring_edges(const SimulationState& w) {
  const std::size_t nodes = w.positions.size();
  check(w.node_body.size() == nodes, "node_body has not one entry per node");
  check_offsets(w.node_spring_offset, nodes, w.node_spring_list.size(), "node_spring_offset");

  // The key of each spring's edge: the node pair (smaller index first), the rest length and the
  // damping, compared by their bits (equal bits, equal arithmetic).
  struct Key {
    std::uint32_t a, b, rest, damping, spring;
    [[nodiscard]] auto edge() const { return std::tie(a, b, rest, damping); }
  };
  std::vector<Key> keys;
  keys.reserve(w.springs.size());
  for (std::size_t s = 0; s < w.springs.size(); ++s) {
    const gpu::Spring& spring = w.springs[s];
    check(spring.a < nodes && spring.b < nodes,
          "spring " + std::to_string(s) + " names a node out of range");
    const std::uint32_t body = w.node_body[spring.a];
    check(body < w.body_params.size(), "node " + std::to_string(spring.a) + " has no body");
    keys.push_back({std::min(spring.a, spring.b), std::max(spring.a, spring.b),
                    std::bit_cast<std::uint32_t>(spring.rest_length),
                    std::bit_cast<std::uint32_t>(w.body_params[body].damping),
                    static_cast<std::uint32_t>(s)});
  }
  std::sort(keys.begin(), keys.end(), [](const Key& x, const Key& y) {
    return std::tie(x.a, x.b, x.rest, x.damping, x.spring) <
           std::tie(y.a, y.b, y.rest, y.damping, y.spring);
  });

  SpringEdges edges;
  std::vector<std::uint32_t> edge_of_spring(w.springs.size());
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const Key& k = keys[i];
    if (i == 0 || k.edge() != keys[i - 1].edge()) {
      edges.a.push_back(k.a);
      edges.b.push_back(k.b);
      edges.rest_length.push_back(std::bit_cast<float>(k.rest));
      edges.damping.push_back(std::bit_cast<float>(k.damping));
    }
    edge_of_spring[k.spring] = static_cast<std::uint32_t>(edges.a.size() - 1);
  }

  edges.node_offset = w.node_spring_offset;
  edges.node_terms.reserve(w.node_spring_list.size());
  for (std::size_t i = 0; i < nodes; ++i) {
    for (std::uint32_t e = w.node_spring_offset[i]; e < w.node_spring_offset[i + 1]; ++e) {
      const std::int32_t tag = w.node_spring_list[e];
      const std::int64_t s = (tag > 0 ? std::int64_t{tag} : -std::int64_t{tag}) - 1;
      check(s >= 0 && static_cast<std::size_t>(s) < w.springs.size(),
            "node_spring_list entry " + std::to_string(e) + " names no spring");
      const std::uint32_t edge = edge_of_spring[static_cast<std::size_t>(s)];
      const float k = w.springs[static_cast<std::size_t>(s)].stiffness;
      edges.node_terms.push_back({edge, i == edges.a[edge] ? k : -k});
    }
  }
  return edges;
}

TetCorners build_tet_corners(const SimulationState& w) {
  const std::size_t nodes = w.positions.size();
  check_offsets(w.node_tet_offset, nodes, w.node_tet_list.size(), "node_tet_offset");

  // Where each corner slot 4 t + k of a stiff tetrahedron lands in the node-major order.
  constexpr std::uint32_t kUnlisted = 0xFFFFFFFFu;
  std::vector<std::uint32_t> slot_of(4 * w.tets.size(), kUnlisted);
  TetCorners corners;
  corners.node_offset.assign(nodes + 1, 0);
  std::uint32_t next = 0;
  for (std::size_t i = 0; i < nodes; ++i) {
    for (std::uint32_t e = w.node_tet_offset[i]; e < w.node_tet_offset[i + 1]; ++e) {
      const std::uint32_t slot = w.node_tet_list[e];
      check(slot < slot_of.size(), "node_tet_list entry " + std::to_string(e) + " names no slot");
      check(slot_of[slot] == kUnlisted,
            "tetrahedron corner slot " + std::to_string(slot) + " is listed twice");
      if (w.tets[slot / 4].stiffness == 0.0f) {
        slot_of[slot] = kUnlisted - 1;  // listed, but contributes +0
        continue;
      }
      slot_of[slot] = next++;
    }
    corners.node_offset[i + 1] = next;
  }

  // A stiff corner no node lists still gets its force written, to a slot no node reads.
  const std::uint32_t spare = next;
  corners.slot_count = next;
  for (std::size_t t = 0; t < w.tets.size(); ++t) {
    const gpu::Tetra& tet = w.tets[t];
    check(tet.a < nodes && tet.b < nodes && tet.c < nodes && tet.d < nodes,
          "tetrahedron " + std::to_string(t) + " names a node out of range");
    if (tet.stiffness == 0.0f) continue;
    corners.tets.push_back(tet);
    for (std::size_t k = 0; k < 4; ++k) {
      const std::uint32_t slot = slot_of[4 * t + k];
      const bool listed = slot < kUnlisted - 1;
      if (!listed) corners.slot_count = spare + 1;
      corners.corner_slot.push_back(listed ? slot : spare);
    }
  }
  return corners;
}

}  // namespace deformcd::sim
