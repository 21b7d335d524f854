#include "cpu/cpu_simulation.h"

#include "core/sim/mass_spring.h"
#include "cpu/mass_spring_batch.h"
#include "cpu/parallel_for.h"

namespace deformcd::cpu {

namespace {

// Nodes per task of the node pass: a node sums about 50 spring terms and 17 tetrahedron corners
// (the paper's models), so a few hundred nodes are enough work per task, and the lion's 4,161
// nodes still make enough tasks for two threads to even out.
constexpr std::size_t kNodeGrain = 256;

}  // namespace

CpuSimulation::CpuSimulation(std::shared_ptr<Executor> executor) : executor_(std::move(executor)) {}

std::string CpuSimulation::device() const {
  return executor_->describe();
}

void CpuSimulation::upload(const SimulationState& state) {
  sim::SpringEdges edges = sim::build_spring_edges(state);
  sim::TetCorners corners = sim::build_tet_corners(state);
  state_ = state;
  edges_ = std::move(edges);
  corners_ = std::move(corners);
  edge_states_.assign(edges_.size(), glm::vec4(0.0f));
  corner_forces_.assign(corners_.slot_count, glm::vec4(0.0f));
  frozen_ = sim::FrozenBodies(state_);
  find_frozen_batches();
}

void CpuSimulation::find_frozen_batches() {
  const std::vector<std::uint8_t>& frozen = frozen_.frozen();
  edge_batch_frozen_ = sim::frozen_batches(edges_.size(), kBatch, state_.node_body, frozen,
                                           [&](std::size_t e, std::uint32_t* n) {
                                             n[0] = edges_.a[e];
                                             n[1] = edges_.b[e];
                                             return 2u;
                                           });
  tet_batch_frozen_ = sim::frozen_batches(corners_.tets.size(), kBatch, state_.node_body, frozen,
                                          [&](std::size_t t, std::uint32_t* n) {
                                            const gpu::Tetra& tet = corners_.tets[t];
                                            n[0] = tet.a;
                                            n[1] = tet.b;
                                            n[2] = tet.c;
                                            n[3] = tet.d;
                                            return 4u;
                                          });
}

sim::NodeBuffers CpuSimulation::node_buffers() {
  return {.node_count = static_cast<std::uint32_t>(state_.positions.size()),
          .host_positions = state_.positions.data(),
          .host_velocities = state_.velocities.data()};
}

void CpuSimulation::set_inverse_masses(std::uint32_t first, std::span<const float> inverse_mass) {
  sim::check_node_range(first, inverse_mass.size(), state_.positions.size());
  for (std::size_t k = 0; k < inverse_mass.size(); ++k) {
    state_.positions[first + k].w = inverse_mass[k];
    state_.velocities[first + k] = glm::vec4(0.0f);
  }
  if (frozen_.set_inverse_masses(first, inverse_mass)) find_frozen_batches();
}

void CpuSimulation::substep(const sim::SubstepConstants& c) {
  executor_->run([&] { step(c); });
  if (frozen_.after_substep()) find_frozen_batches();
}

void CpuSimulation::step(const sim::SubstepConstants& c) {
  SimulationState& w = state_;
  const sim::SpringEdges& e = edges_;
  const std::size_t edge_count = e.size();
  // SpringUpdate, once per edge, and TetUpdate in one loop (one join fewer), kBatch elements
  // per iteration in SIMD lanes: iterations [0, edge batches) are edges, the rest stiff
  // tetrahedra; a last partial batch runs the scalar functions. Each writes only its own slots.
  const std::size_t edge_batches = (edge_count + kBatch - 1) / kBatch;
  const std::size_t tet_count = corners_.tets.size();
  const std::size_t tet_batches = (tet_count + kBatch - 1) / kBatch;
  parallel_for(
      edge_batches + tet_batches,
      [&](std::size_t batch) {
        if (batch < edge_batches) {
          if (edge_batch_frozen_[batch] != 0u) return;  // frozen bodies' edges: as they are
          const std::size_t j = batch * kBatch;
          if (j + kBatch <= edge_count) {
            spring_edge_states(w.positions.data(), w.velocities.data(), &e.a[j], &e.b[j],
                               &e.rest_length[j], &e.damping[j], &edge_states_[j]);
            return;
          }
          for (std::size_t k = j; k < edge_count; ++k) {
            const std::uint32_t a = e.a[k], b = e.b[k];
            edge_states_[k] = sim::spring_edge_state(
                glm::vec3(w.positions[a]), glm::vec3(w.positions[b]), glm::vec3(w.velocities[a]),
                glm::vec3(w.velocities[b]), e.rest_length[k], e.damping[k]);
          }
          return;
        }
        if (tet_batch_frozen_[batch - edge_batches] != 0u) return;
        const std::size_t t0 = (batch - edge_batches) * kBatch;
        if (t0 + kBatch <= tet_count) {
          tet_volume_forces(w.positions.data(), &corners_.tets[t0], &corners_.corner_slot[4 * t0],
                            corner_forces_.data());
          return;
        }
        for (std::size_t t = t0; t < tet_count; ++t) {
          const gpu::Tetra& tet = corners_.tets[t];
          glm::vec3 f[4];
          sim::tet_volume_forces(glm::vec3(w.positions[tet.a]), glm::vec3(w.positions[tet.b]),
                                 glm::vec3(w.positions[tet.c]), glm::vec3(w.positions[tet.d]),
                                 tet.rest_volume, tet.stiffness, f);
          for (std::size_t k = 0; k < 4; ++k)
            corner_forces_[corners_.corner_slot[4 * t + k]] = glm::vec4(f[k], 0.0f);
        }
      },
      kDefaultGrain / kBatch);
  const std::vector<std::uint8_t>& frozen = frozen_.frozen();
  // NodeForce: each node sums its springs' terms in its list order, then its tetrahedron
  // corners in theirs; NodeUpdate: integrate it. Both per node, fused on the CPU since nothing
  // reads another node's force.
  parallel_for(
      w.positions.size(),
      [&](std::size_t i) {
        if (frozen[w.node_body[i]] != 0u) return;  // stays as the last substep left it
        // Summed in 4 SIMD lanes, one vec4 load and one multiply-add pair per term: lanes x, y
        // and z are the vec3 sums of sim::spring_term bit for bit (lanes are independent), lane
        // w is unused.
        Lanes springs(0.0f);
        for (std::uint32_t k = e.node_offset[i]; k < e.node_offset[i + 1]; ++k) {
          const sim::EdgeTerm term = e.node_terms[k];
          const glm::vec4& state = edge_states_[term.edge];
          springs +=
              Lanes(term.signed_stiffness * state.w) * Lanes(&state.x, stdx::element_aligned);
        }
        Lanes tets(0.0f);
        for (std::uint32_t k = corners_.node_offset[i]; k < corners_.node_offset[i + 1]; ++k)
          tets += Lanes(&corner_forces_[k].x, stdx::element_aligned);
        const glm::vec3 f =
            glm::vec3(springs[0], springs[1], springs[2]) + glm::vec3(tets[0], tets[1], tets[2]);
        w.forces[i] = glm::vec4(f, 0.0f);
        sim::integrate_node(w.positions[i], w.velocities[i], f,
                            glm::vec3(w.body_params[w.node_body[i]].carry_velocity), c);
      },
      kNodeGrain);
}

}  // namespace deformcd::cpu
