#include <string>

#include "deformcd/error.h"
#include "deformcd/simulation_state.h"

namespace deformcd {

namespace {

// The volume energy is k (V - V0)^2 / (2 L^3), L the tetrahedron's mean rest edge length. For a
// regular tetrahedron L^3 ~ 8.5 V0, as in Teschner et al.'s k (V - V0)^2 / (2 V0); for a sliver
// (V0 -> 0) dividing by V0 would make it arbitrarily stiff and the explicit step unstable,
// dividing by L^3 keeps its stiffness in line with its springs'.
float volume_force_coefficient(float volume_stiffness, float mean_edge) {
  return volume_stiffness / (mean_edge * mean_edge * mean_edge);
}

void append_body(SimulationState& w, const BodyInit& init, std::uint32_t body_index,
                 std::uint32_t face_offset) {
  const Body& b = init.body;
  gpu::ObjectInfo info{};
  info.node_offset = static_cast<std::uint32_t>(w.positions.size());
  info.node_count = static_cast<std::uint32_t>(b.positions.size());
  info.face_offset = face_offset;
  info.face_count = static_cast<std::uint32_t>(b.faces.size());
  info.spring_offset = static_cast<std::uint32_t>(w.springs.size());
  info.spring_count = static_cast<std::uint32_t>(b.springs.size());
  info.tet_count = static_cast<std::uint32_t>(b.tetrahedra.size());
  w.objects.push_back(info);

  const std::string name = init.name.empty() ? "body " + std::to_string(body_index) : init.name;
  if (b.faces.empty()) throw InputError(name, "body has no surface faces");
  std::vector<bool> fixed(b.positions.size(), false);
  for (std::uint32_t n : init.fixed) {
    if (n >= b.positions.size()) {
      throw InputError(name, "fixed node " + std::to_string(n) + " is out of range (the body has " +
                                 std::to_string(b.positions.size()) + " nodes)");
    }
    fixed[n] = true;
  }
  for (std::size_t i = 0; i < b.positions.size(); ++i) {
    const float inverse_mass = fixed[i] ? 0.0f : 1.0f / b.node_mass[i];
    w.positions.emplace_back(glm::vec3(b.positions[i]), inverse_mass);
    w.velocities.emplace_back(glm::vec3(b.velocities[i]), 0.0f);
    w.node_body.push_back(body_index);
  }
  for (const gpu::Spring& s : b.springs) {
    w.springs.push_back(
        {s.a + info.node_offset, s.b + info.node_offset, s.rest_length, s.stiffness});
  }
  w.objects.back().tet_offset = static_cast<std::uint32_t>(w.tets.size());
  for (std::size_t t = 0; t < b.tetrahedra.size(); ++t) {
    const Tetrahedron& tet = b.tetrahedra[t];
    w.tets.push_back({tet[0] + info.node_offset, tet[1] + info.node_offset,
                      tet[2] + info.node_offset, tet[3] + info.node_offset, b.tet_rest_volume[t],
                      volume_force_coefficient(init.volume_stiffness, b.tet_rest_edge[t]), 0.0f,
                      0.0f});
  }
  w.body_params.push_back({glm::vec4(init.carry_velocity, 0.0f), init.damping, 0.0f, 0.0f, 0.0f});
  w.body_names.push_back(name);
}

// Compressed per-node lists: `for_each_entry(emit)` calls emit(node, value) for every entry in
// the order the lists must keep; the result holds offsets (nodes + 1) and the values.
template <class Value, class ForEachEntry>
void build_csr(std::size_t nodes, const ForEachEntry& for_each_entry,
               std::vector<std::uint32_t>& offset, std::vector<Value>& list) {
  offset.assign(nodes + 1, 0);
  for_each_entry([&](std::uint32_t node, Value) { ++offset[node + 1]; });
  for (std::size_t i = 1; i < offset.size(); ++i)
    offset[i] += offset[i - 1];
  list.assign(offset.back(), Value{});
  std::vector<std::uint32_t> fill(offset.begin(), offset.end() - 1);
  for_each_entry([&](std::uint32_t node, Value value) { list[fill[node]++] = value; });
}

// Per-node incident springs, in increasing spring order: +(s+1) at end a, -(s+1) at end b.
void build_node_springs(SimulationState& w) {
  build_csr<std::int32_t>(
      w.positions.size(),
      [&](auto emit) {
        for (std::size_t s = 0; s < w.springs.size(); ++s) {
          const auto tag = static_cast<std::int32_t>(s + 1);
          emit(w.springs[s].a, tag);
          emit(w.springs[s].b, -tag);
        }
      },
      w.node_spring_offset, w.node_spring_list);
}

// Per-node tetrahedron corners: slot 4 t + k for corner k of tetrahedron t, in slot order.
void build_node_tets(SimulationState& w) {
  build_csr<std::uint32_t>(
      w.positions.size(),
      [&](auto emit) {
        for (std::size_t t = 0; t < w.tets.size(); ++t) {
          const gpu::Tetra& tet = w.tets[t];
          const std::uint32_t corners[4] = {tet.a, tet.b, tet.c, tet.d};
          for (std::uint32_t k = 0; k < 4; ++k) {
            emit(corners[k], static_cast<std::uint32_t>(4 * t + k));
          }
        }
      },
      w.node_tet_offset, w.node_tet_list);
}

}  // namespace

SimulationState assemble_simulation(const std::vector<BodyInit>& bodies) {
  SimulationState w;
  std::uint32_t faces = 0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    append_body(w, bodies[i], static_cast<std::uint32_t>(i), faces);
    faces += static_cast<std::uint32_t>(bodies[i].body.faces.size());
  }
  w.forces.assign(w.positions.size(), glm::vec4(0.0f));
  w.spring_forces.assign(w.springs.size(), glm::vec4(0.0f));
  w.tet_forces.assign(4 * w.tets.size(), glm::vec4(0.0f));
  build_node_springs(w);
  build_node_tets(w);
  return w;
}

}  // namespace deformcd
