#include "cpu/cpu_contact_response.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <string>
#include <thread>
#include <utility>

#include <tbb/parallel_invoke.h>

#include "cpu/parallel_for.h"
#include "deformcd/error.h"

namespace deformcd::cpu {

namespace {

// A projection with fewer acting constraints than this sweeps on one thread: starting the
// second costs more than the half it would take (8 sweeps of 512 constraints: about 0.3 ms).
constexpr std::size_t kTwoThreadsFrom = 512;
// Empty node slots between the halves' copies: 2 x 32 bytes, a cache line.
constexpr std::uint32_t kGapSlots = 2;
// A thread waiting for the other's half spins this long, then yields its core.
constexpr int kSpinsBeforeYield = 4096;

}  // namespace

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
  if (constraints.node_motion.size() != nodes || constraints.window_start.size() != nodes) {
    throw Error("CpuContactResponse: the constraints' node_motion (" +
                std::to_string(constraints.node_motion.size()) + ") and window_start (" +
                std::to_string(constraints.window_start.size()) + ") are not one per node (" +
                std::to_string(nodes) + ")");
  }
  frame_start_.resize(nodes);
  // The slide stamps outlive a window (a contact's slide goes on across searches): set only for
  // new nodes, to a substep no projection has.
  if (slid_.size() != nodes) slid_.assign(nodes, response::kNeverSlid);
  // The guard stamps: 0, which no projection has (they count from 1), for new nodes.
  if (guard_.size() != nodes) guard_.assign(nodes, 0u);
  start_.assign(nodes, glm::vec4(0.0f));
  counts_.assign(2u * nodes, 0u);
  slot_.assign(nodes, 0u);
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
    parallel_select(
        pairs.size(), [&](std::size_t p) { return active_[p] != 0u; }, acting_, block_starts_);
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
    // The acting constraints' colours, and the sweep's work items: each run of colours whole,
    // or its two halves (either may run on either thread, at the same time: a constraint of one
    // reads only nodes its half writes, so the bits are those of a sweep colour by colour, GL's).
    // An item waits only for the items of the runs before its own.
    const auto split = static_cast<std::uint32_t>(
        std::lower_bound(acting_.begin(), acting_.end(), first_volume_) - acting_.begin());
    sweep_.colour(pairs, acting_, split, constraints_->window_start);
    const std::vector<std::uint32_t>& order = sweep_.order();
    const std::vector<std::uint32_t>& colour_begin = sweep_.colour_begin();
    const std::vector<std::uint32_t>& half_begin = sweep_.half_begin();
    items_.clear();
    swept_.clear();
    for (const response::SweepOrder::Run& run : sweep_.runs()) {
      const auto stage = static_cast<std::uint32_t>(items_.size());
      for (std::uint32_t half = 0; half < (run.halves ? 2u : 1u); ++half) {
        const auto begin = static_cast<std::uint32_t>(swept_.size());
        for (std::uint32_t c = run.first; c < run.end; ++c) {
          const std::uint32_t b = run.halves && half == 1u ? half_begin[c] : colour_begin[c];
          const std::uint32_t e = run.halves && half == 0u ? half_begin[c] : colour_begin[c + 1u];
          swept_.insert(swept_.end(), order.begin() + b, order.begin() + e);
        }
        items_.push_back({begin, static_cast<std::uint32_t>(swept_.size()), stage});
      }
    }
    // The constraints' copies in that order (the sweeps read compact blocks: on the impact,
    // 2,200 acting constraints of 55,000 listed; and each half's thread writes its impulses and
    // slides in a block of its own, not in the other's cache lines).
    swept_pairs_.resize(acting_.size());
    for (std::uint32_t e = 0; e < acting_.size(); ++e)
      swept_pairs_[e] = pairs[acting_[swept_[e]]];
    // The sweeps correct copies of their nodes' positions and velocities: the first half's
    // nodes, a cache line's gap, the second half's. So the two halves' threads never write to
    // one cache line (in the node arrays a fifth of the lines the impact's halves touch hold
    // nodes of both, and the threads passing them to and fro made two threads' sweeps slower
    // than one's); and the sweeps read a compact block.
    std::uint32_t slots = 0;
    for (std::uint32_t half = 0; half < 2u; ++half) {
      if (half == 1u) slots += kGapSlots + (kGapSlots - slots % kGapSlots) % kGapSlots;
      for (const std::uint32_t n : touched_)
        if (sweep_.half_of(constraints_->window_start[n]) == half) slot_[n] = slots++;
    }
    local_.resize(slots);
    for (const std::uint32_t n : touched_)
      local_[slot_[n]] = {nodes_.host_positions[n], nodes_.host_velocities[n]};
    swept_slots_.resize(acting_.size());
    for (std::uint32_t e = 0; e < acting_.size(); ++e)
      for (std::uint32_t i = 0; i < 4u; ++i)
        swept_slots_[e][i] = slot_[swept_pairs_[e].nodes[i]];
    impulses_.resize(3u * acting_.size());
    slides_.resize(acting_.size());
    // One sweep: in the colours' order (the contacts', then the volume constraints'), each
    // constraint solved on its nodes as the constraints before left them and applied at once;
    // no two constraints of a colour share a node, so GL's sweep, which solves a colour's
    // constraints at once, gives the same bits. `last`: the friction's last-iteration rule
    // applies, and the slides are stamped after the sweep (a contact later in it must read the
    // last substep's stamps).
    const auto solve = [&](std::uint32_t e, bool first_iteration, bool last) {
      const gpu::ContactPair& pair = swept_pairs_[e];
      const std::array<std::uint32_t, 4>& slot = swept_slots_[e];
      const bool contact = swept_[e] < split;
      glm::vec4 x[4], v[4];
      std::uint32_t count[4] = {0u, 0u, 0u, 0u};
      for (std::uint32_t i = 0; i < 4u; ++i) {
        x[i] = local_[slot[i]].x;
        v[i] = local_[slot[i]].v;
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
                              history, &impulses_[3u * e], correction);
      std::uint8_t slides = 0u;
      for (std::uint32_t i = 0; i < 4u; ++i) {
        response::apply_correction(local_[slot[i]].x, local_[slot[i]].v,
                                   glm::vec3(correction[2u * i]),
                                   glm::vec3(correction[2u * i + 1u]));
        if (correction[2u * i + 1u].w > 0.0f) slides |= static_cast<std::uint8_t>(1u << i);
      }
      slides_[e] = slides;
    };
    const auto sweep_item = [&](const SweepItem& item, bool first_iteration, bool last) {
      for (std::uint32_t e = item.begin; e < item.end; ++e)
        solve(e, first_iteration, last);
    };
    // `count` sweeps, the first of them the projection's first when `starts`, the last with the
    // friction's last-iteration rule; then the slide stamps. On two threads when there is work
    // enough for both, in one parallel call: the threads claim the items in order, so the
    // earliest unfinished item is always running (one thread alone runs them all in order). A
    // wait at each colour instead (a parallel loop per colour, or threads taking chunks of each
    // colour in turn) made the sweeps 1.4 x as long as on one thread, on the impact a
    // projection's 42 colours holding 54 constraints on average (half of them 12 or fewer) at
    // about 70 ns a constraint; and a parallel call per run cost more than the halves gained
    // (the second thread woken each time).
    const auto iterate = [&](int count, bool starts) {
      const auto per_sweep = static_cast<std::uint32_t>(items_.size());
      const std::uint32_t total = static_cast<std::uint32_t>(count) * per_sweep;
      std::atomic<std::uint32_t> next{0u};
      std::atomic<std::uint32_t> done{0u};
      const auto work = [&] {
        for (std::uint32_t claimed = next.fetch_add(1u); claimed < total;
             claimed = next.fetch_add(1u)) {
          const std::uint32_t sweep = claimed / per_sweep;
          const SweepItem& item = items_[claimed % per_sweep];
          const std::uint32_t after = sweep * per_sweep + item.stage;  // items done before it
          for (int spins = 0; done.load(std::memory_order_acquire) < after; ++spins)
            if (spins > kSpinsBeforeYield) std::this_thread::yield();
          sweep_item(item, starts && sweep == 0u, sweep + 1u == static_cast<std::uint32_t>(count));
          done.fetch_add(1u, std::memory_order_release);
        }
      };
      if (acting_.size() >= kTwoThreadsFrom && executor_->threads() > 1) {
        tbb::parallel_invoke(work, work);
      } else {
        work();
      }
      // A free node one of whose contacts slides on records the substep (in the sweep's order:
      // every writer writes the same stamp). Volume constraints never slide.
      for (std::uint32_t e = 0; e < acting_.size(); ++e) {
        if (slides_[e] == 0u) continue;
        for (std::uint32_t i = 0; i < 4u; ++i) {
          const std::uint32_t n = swept_pairs_[e].nodes[i];
          if ((slides_[e] >> i & 1u) != 0u && nodes_.host_positions[n].w > 0.0f)
            slid_[n] = substep_;
        }
      }
    };
    // Whether an active constraint is still violated (contact_violated): an OR, the same
    // whatever the order, so the search may stop at the first it finds. It looks first at the
    // one found last time: in a projection that iterates on, a few tetrahedra (or contacts)
    // stay violated over its extra iterations, and the whole list's scan each iteration cost
    // as much as a tenth of the response on the impact.
    std::uint32_t last_violated = 0u;  // an index into swept_pairs_ (any, at first)
    const auto is_violated = [&](std::uint32_t e) {
      const gpu::ContactPair& pair = swept_pairs_[e];
      const std::array<std::uint32_t, 4>& slot = swept_slots_[e];
      const glm::vec4 x[4] = {local_[slot[0]].x, local_[slot[1]].x, local_[slot[2]].x,
                              local_[slot[3]].x};
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
    if (iterations > 0) iterate(iterations, true);
    // More while the solve has not converged, to kMaxIterationFactor x the iterations asked.
    iterations_done_ = iterations;
    while (iterations_done_ < response::kMaxIterationFactor * iterations && violated()) {
      iterate(1, false);
      ++iterations_done_;
    }
    for (const std::uint32_t n : touched_) {
      nodes_.host_positions[n] = local_[slot_[n]].x;
      nodes_.host_velocities[n] = local_[slot_[n]].v;
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
