#pragma once
// The narrow phase every CPU broad phase ends in: the exact test of one face pair, and where the
// intersecting pairs and the test count go while many threads run tests at once.

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <limits>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "core/collision/tri_tri_intersection.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::cpu {

// What one thread found: its intersecting pairs and how many pairs it tested.
struct ThreadPairs {
  std::vector<gpu::FacePair> pairs;
  std::uint64_t candidates = 0;
};

// Per-thread result lists: a test appends to its own thread's list without locking. The lists
// keep their capacity from pass to pass, so a pass allocates nothing once warm.
class PairCollector {
 public:
  [[nodiscard]] ThreadPairs& local() { return lists_.local(); }

  // Moves every thread's pairs to the end of `out` (in no particular order: the caller sorts)
  // and returns the summed test count; the lists are left empty for the next pass.
  std::uint64_t gather(std::vector<gpu::FacePair>& out) {
    std::uint64_t candidates = 0;
    for (ThreadPairs& t : lists_) {
      out.insert(out.end(), t.pairs.begin(), t.pairs.end());
      candidates += t.candidates;
      t.pairs.clear();
      t.candidates = 0;
    }
    return candidates;
  }

 private:
  tbb::enumerable_thread_specific<ThreadPairs> lists_;
};

// The exact triangle-triangle test over the positions of the current pass. face_a must be the
// face of the lower-numbered body, as in FacePair.
struct NarrowPhase {
  const glm::vec4* positions;
  const gpu::Face* faces;
  std::uint32_t* flags;  // SSBO 5

  // Tests the pair and appends it to `out` when the faces intersect; counts the test.
  void test(std::uint32_t face_a, std::uint32_t face_b, ThreadPairs& out) const {
    ++out.candidates;
    const gpu::Face& fa = faces[face_a];
    const gpu::Face& fb = faces[face_b];
    const glm::vec3 ta[3] = {glm::vec3(positions[fa.a]), glm::vec3(positions[fa.b]),
                             glm::vec3(positions[fa.c])};
    const glm::vec3 tb[3] = {glm::vec3(positions[fb.a]), glm::vec3(positions[fb.b]),
                             glm::vec3(positions[fb.c])};
    const collision::TriTriResult hit = collision::tri_tri_intersect(ta, tb);
    if (!hit.intersect) return;
    // Several threads may flag one face; the value written is the same.
    std::atomic_ref<std::uint32_t>(flags[face_a]).store(1u, std::memory_order_relaxed);
    std::atomic_ref<std::uint32_t>(flags[face_b]).store(1u, std::memory_order_relaxed);
    out.pairs.push_back({face_a, face_b, hit.coplanar ? 1u : 0u, 0u,
                         glm::vec4(hit.segment[0], 0.0f), glm::vec4(hit.segment[1], 0.0f)});
  }
};

// A 64-bit count in a 32-bit device counter: saturates rather than wraps.
[[nodiscard]] inline std::uint32_t saturate_u32(std::uint64_t count) {
  return static_cast<std::uint32_t>(
      std::min<std::uint64_t>(count, std::numeric_limits<std::uint32_t>::max()));
}

}  // namespace deformcd::cpu
