#include "cpu/cpu_contact_response.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <utility>

#include "cpu/parallel_for.h"
#include "deformcd/error.h"

namespace deformcd::cpu {

CpuContactResponse::CpuContactResponse(sim::SimulationBackend& simulation,
                                       std::shared_ptr<Executor> executor)
    : simulation_(simulation), executor_(std::move(executor)) {}

void CpuContactResponse::take(const response::FrameConstraints& constraints) {
  first_volume_ = response::first_volume_constraint(constraints.pairs);
  constraints_ = &constraints;
  active_.assign(constraints_->pairs.size(), 0u);
  acting_.clear();
}

void CpuContactResponse::begin_frame(const response::FrameConstraints& constraints) {
  nodes_ = simulation_.node_buffers();
  if (nodes_.host_positions == nullptr || nodes_.host_velocities == nullptr) {
    throw Error("CpuContactResponse: the simulation keeps no nodes in host memory");
  }
  take(constraints);
  const std::size_t nodes = nodes_.node_count;
  frame_start_.resize(nodes);
  // The slide stamps outlive a window (a contact's slide goes on across searches): set only for
  // new nodes, to a substep no projection has.
  if (slid_.size() != nodes) slid_.assign(nodes, response::kNeverSlid);
  // The guard stamps: 0, which no projection has (they count from 1), for new nodes.
  if (guard_.size() != nodes) guard_.assign(nodes, 0u);
  start_.assign(nodes, glm::vec4(0.0f));
  counts_.assign(2u * nodes, 0u);
  touched_.clear();
  executor_->run([&] {
    parallel_for(nodes, [&](std::size_t i) {
      frame_start_[i] =
          glm::vec4(glm::vec3(nodes_.host_positions[i]), constraints_->node_motion[i].w);
    });
  });
  watch_reachable_nodes();
}

void CpuContactResponse::update_frame(const response::FrameConstraints& constraints) {
  take(constraints);
  // A widening raises finite reaches only, so the watched nodes stay those begin_frame listed.
  for (const std::uint32_t i : watched_)
    frame_start_[i].w = constraints_->node_motion[i].w;
}

void CpuContactResponse::watch_reachable_nodes() {
  // A node with an infinite reach (on no collision surface: a body's interior nodes) is in no
  // constraint and never strays, so the per-substep passes leave it out.
  watched_.clear();
  for (std::uint32_t i = 0; i < frame_start_.size(); ++i)
    if (!std::isinf(frame_start_[i].w)) watched_.push_back(i);
}

void CpuContactResponse::load_window_start(const gpu::ContactPair& pair,
                                           glm::vec3 window_start[4]) const {
  const bool reads = response::reads_window_start(pair);
  for (std::uint32_t k = 0; k < 4u; ++k)
    window_start[k] = reads ? glm::vec3(frame_start_[pair.nodes[k]]) : glm::vec3(0.0f);
}

bool CpuContactResponse::project(const response::ContactConstants& k, int iterations) {
  if (constraints_ == nullptr) throw Error("CpuContactResponse::project before begin_frame()");
  ++substep_;
  std::atomic<bool> any_strayed{false};  // an OR: the same whatever the order
  const std::vector<gpu::ContactPair>& pairs = constraints_->pairs;
  executor_->run([&] {
    // Deviation pass, activity pass (only awake constraints look at their geometry), count,
    // then the sweeps; the deviation and stray passes visit only the watched nodes (those a
    // constraint can name).
    parallel_for(watched_.size(), [&](std::size_t w) {
      const std::uint32_t i = watched_[w];
      start_[i] =
          response::projection_start(nodes_.host_positions[i], nodes_.host_velocities[i], k.h,
                                     frame_start_[i], constraints_->node_motion[i], k.elapsed);
    });
    parallel_for(
        first_volume_,
        [&](std::size_t p) {
          const gpu::ContactPair& pair = pairs[p];
          const float deviation[4] = {start_[pair.nodes[0]].w, start_[pair.nodes[1]].w,
                                      start_[pair.nodes[2]].w, start_[pair.nodes[3]].w};
          bool active = response::contact_awake(pair, deviation, k.elapsed);
          if (active) {
            const glm::vec4 x[4] = {
                nodes_.host_positions[pair.nodes[0]], nodes_.host_positions[pair.nodes[1]],
                nodes_.host_positions[pair.nodes[2]], nodes_.host_positions[pair.nodes[3]]};
            glm::vec3 window_start[4];
            load_window_start(pair, window_start);
            active = response::contact_active(pair, x, window_start);
          }
          active_[p] = active ? 1u : 0u;
          // The nodes of an active contact that guards volume constraints are stamped with this
          // projection: every writer of a node writes the same value.
          if (active && response::guards_volumes(pair)) {
            for (const std::uint32_t n : pair.nodes)
              std::atomic_ref<std::uint32_t>(guard_[n]).store(substep_, std::memory_order_relaxed);
          }
        },
        1024);
    // The volume constraints, which read the stamps.
    parallel_for(
        pairs.size() - first_volume_,
        [&](std::size_t a) {
          const std::size_t p = first_volume_ + a;
          const gpu::ContactPair& pair = pairs[p];
          glm::vec4 x[4], v[4];
          bool guarded = false;
          for (std::uint32_t i = 0; i < 4u; ++i) {
            x[i] = nodes_.host_positions[pair.nodes[i]];
            v[i] = nodes_.host_velocities[pair.nodes[i]];
            guarded = guarded || guard_[pair.nodes[i]] == substep_;
          }
          active_[p] = response::volume_watched(pair, x, v, k.h, guarded) ? 1u : 0u;
        },
        1024);
    // The count pass, summed from the compacted list: the integer counts do not depend on the
    // order, and equal the GL count pass's over each node's list. The last substep's touched
    // nodes are the only nonzero counts.
    acting_.clear();
    for (std::uint32_t p = 0; p < pairs.size(); ++p)
      if (active_[p] != 0u) acting_.push_back(p);
    for (const std::uint32_t n : touched_)
      counts_[2u * n] = counts_[2u * n + 1u] = 0u;
    touched_.clear();
    for (const std::uint32_t p : acting_) {
      const std::uint32_t group = p < first_volume_ ? 0u : 1u;
      for (const std::uint32_t n : pairs[p].nodes) {
        if (counts_[2u * n] + counts_[2u * n + 1u] == 0u) touched_.push_back(n);
        ++counts_[2u * n + group];
      }
    }
    // The acting constraints' copies, in acting order (the sweeps read compact blocks: on the
    // impact, 2,200 acting constraints of 55,000 listed), and their colours.
    acting_pairs_.resize(acting_.size());
    for (std::uint32_t a = 0; a < acting_.size(); ++a)
      acting_pairs_[a] = pairs[acting_[a]];
    impulses_.resize(3u * acting_.size());
    slides_.resize(acting_.size());
    const auto split = static_cast<std::uint32_t>(
        std::lower_bound(acting_.begin(), acting_.end(), first_volume_) - acting_.begin());
    sweep_.colour(pairs, acting_, split, static_cast<std::uint32_t>(nodes_.node_count));
    const std::vector<std::uint32_t>& order = sweep_.order();
    // One sweep: in the colours' order (the contacts', then the volume constraints'), each
    // constraint solved on its nodes as the constraints before left them and applied at once;
    // no two constraints of a colour share a node, so GL's sweep, which solves a colour's
    // constraints at once, gives the same bits. `last`: the friction's last-iteration rule
    // applies, and the slides are stamped after the sweep (a contact later in it must read the
    // last substep's stamps).
    const auto solve = [&](std::uint32_t a, bool first_iteration, bool last) {
      const gpu::ContactPair& pair = acting_pairs_[a];
      const bool contact = a < split;
      glm::vec4 x[4], v[4];
      std::uint32_t count[4] = {0u, 0u, 0u, 0u};
      for (std::uint32_t i = 0; i < 4u; ++i) {
        x[i] = nodes_.host_positions[pair.nodes[i]];
        v[i] = nodes_.host_velocities[pair.nodes[i]];
      }
      // A volume constraint reads no count, projection start, window start or slide history
      // (solve_volume): their loads are left out, and zeros passed.
      glm::vec4 start[4] = {glm::vec4(0.0f), glm::vec4(0.0f), glm::vec4(0.0f), glm::vec4(0.0f)};
      glm::vec3 window_start[4] = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f),
                                   glm::vec3(0.0f)};
      std::uint32_t history = response::kNoneSlid;
      if (contact) {
        std::uint32_t slid[4];
        for (std::uint32_t i = 0; i < 4u; ++i) {
          count[i] = counts_[2u * pair.nodes[i]];
          start[i] = start_[pair.nodes[i]];
          slid[i] = slid_[pair.nodes[i]];
        }
        load_window_start(pair, window_start);
        history = response::slid_before(x, slid, substep_);
      }
      glm::vec4 correction[8];
      response::solve_contact(pair, x, v, count, start, window_start, k, first_iteration, last,
                              history, &impulses_[3u * a], correction);
      std::uint8_t slides = 0u;
      for (std::uint32_t i = 0; i < 4u; ++i) {
        response::apply_correction(
            nodes_.host_positions[pair.nodes[i]], nodes_.host_velocities[pair.nodes[i]],
            glm::vec3(correction[2u * i]), glm::vec3(correction[2u * i + 1u]));
        if (correction[2u * i + 1u].w > 0.0f) slides |= static_cast<std::uint8_t>(1u << i);
      }
      slides_[a] = slides;
    };
    // On one thread: each colour must see what the one before it wrote, and on the impact a
    // projection's 42 colours hold 54 constraints on average but half of them 12 or fewer (a
    // constraint is about 70 ns of work). Split between two threads (a parallel loop per
    // colour, or threads taking chunks of each colour in turn with a wait at each colour, even
    // with each thread's share of the nodes kept its own) the sweeps took 1.4 x as long as on
    // one, the waits and the nodes passed from core to core (a colour's nodes are the next
    // one's) costing more than the colours' work: the GPU's work group sweeps them instead.
    const auto iterate = [&](bool first_iteration, bool last) {
      for (const std::uint32_t a : order)
        solve(a, first_iteration, last);
      if (!last) return;
      // A free node one of whose contacts slides on records the substep (in acting order: every
      // writer writes the same stamp).
      for (std::uint32_t a = 0; a < split; ++a) {
        if (slides_[a] == 0u) continue;
        for (std::uint32_t i = 0; i < 4u; ++i) {
          const std::uint32_t n = acting_pairs_[a].nodes[i];
          if ((slides_[a] >> i & 1u) != 0u && nodes_.host_positions[n].w > 0.0f)
            slid_[n] = substep_;
        }
      }
    };
    // Whether an active constraint is still violated (contact_violated): an OR, the same
    // whatever the order, so the search may stop at the first it finds. It looks first at the
    // one found last time: in a projection that iterates on, a few tetrahedra (or contacts)
    // stay violated over its extra iterations, and the whole list's scan each iteration cost
    // as much as a tenth of the response on the impact.
    std::uint32_t last_violated = 0u;  // an index into acting_ (any, at first)
    const auto is_violated = [&](std::uint32_t a) {
      const gpu::ContactPair& pair = acting_pairs_[a];
      const glm::vec4 x[4] = {
          nodes_.host_positions[pair.nodes[0]], nodes_.host_positions[pair.nodes[1]],
          nodes_.host_positions[pair.nodes[2]], nodes_.host_positions[pair.nodes[3]]};
      glm::vec3 window_start[4];
      load_window_start(pair, window_start);
      return response::contact_violated(pair, x, window_start);
    };
    const auto violated = [&] {
      if (acting_.empty()) return false;
      if (is_violated(last_violated)) return true;
      std::atomic<std::uint32_t> found{0xFFFFFFFFu};  // any violated one's index
      parallel_for(
          acting_.size(),
          [&](std::size_t a) {
            if (found.load(std::memory_order_relaxed) != 0xFFFFFFFFu) return;
            if (is_violated(static_cast<std::uint32_t>(a)))
              found.store(static_cast<std::uint32_t>(a), std::memory_order_relaxed);
          },
          256);
      if (found.load() == 0xFFFFFFFFu) return false;
      last_violated = found.load();
      return true;
    };
    for (int iteration = 0; iteration < iterations; ++iteration)
      iterate(iteration == 0, iteration + 1 == iterations);
    // More while the solve has not converged, to kMaxIterationFactor x the iterations asked.
    iterations_done_ = iterations;
    while (iterations_done_ < response::kMaxIterationFactor * iterations && violated()) {
      iterate(false, true);
      ++iterations_done_;
    }
    // The strays, as GL's stray pass flags them: an untouched node is where the deviation pass
    // measured it. An unwatched node never strays (its reach is infinite).
    parallel_for(watched_.size(), [&](std::size_t w) {
      const std::uint32_t i = watched_[w];
      const glm::vec4& x = nodes_.host_positions[i];
      const bool beyond =
          counts_[2u * i] + counts_[2u * i + 1u] != 0u
              ? response::strayed(x, frame_start_[i], constraints_->node_motion[i], k.elapsed)
              : response::beyond_reach(start_[i].w, x, frame_start_[i]);
      if (beyond) any_strayed.store(true, std::memory_order_relaxed);
    });
  });
  return any_strayed.load();
}

}  // namespace deformcd::cpu
