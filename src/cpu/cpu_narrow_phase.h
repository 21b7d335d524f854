#pragma once
// The narrow phase every CPU broad phase ends in: the exact test of one face pair, and where the
// intersecting pairs and the test count go while many threads run tests at once.

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <limits>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "core/collision/face_pair_intersection.h"
#include "core/collision/vertex_positions.h"
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

// The exact test of one face pair over the positions of the current pass
// (collision::face_pair_intersect: faces sharing an edge are neighbours, not a contact; faces
// sharing a node must meet elsewhere too). Face pairs are ordered, face_a < face_b: in a pair
// of bodies face_a is the lower-numbered body's, and within one body (self-collision, which
// broad phases enumerate both ways) the other order is skipped here, before it is counted.
struct NarrowPhase {
  collision::VertexPositions positions;
  const gpu::Face* faces;
  std::uint32_t* flags;  // SSBO 5

  // Tests the pair and appends it to `out` when the faces intersect; counts the test.
  void test(std::uint32_t face_a, std::uint32_t face_b, ThreadPairs& out) const {
    if (face_a >= face_b) return;
    ++out.candidates;
    const collision::TriTriResult hit =
        collision::face_pair_intersect(faces[face_a], faces[face_b], positions);
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
