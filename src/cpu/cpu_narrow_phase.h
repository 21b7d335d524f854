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
#include "core/collision/tri_tri_plane_step.h"
#include "core/collision/vertex_positions.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::cpu {

// What one thread found: its intersecting pairs and how many pairs it tested.
struct ThreadPairs {
  std::vector<gpu::FacePair> pairs;
  std::uint64_t candidates = 0;
  // Room for the triangle geometry a batch's tests make without keeping it in the shared cache
  // (FaceGeometryCache::get with several threads), two per candidate of a batch.
  std::vector<collision::TriangleGeometry> own;
};

// Candidate face pairs (face_a < face_b) waiting for their tests (NarrowPhase::add).
struct CandidateBatch {
  static constexpr std::uint32_t kSize = 64;
  std::uint32_t face_a[kSize];
  std::uint32_t face_b[kSize];
  std::uint32_t count = 0;
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

// Per face, its triangle's geometry in the current pass (collision::TriangleGeometry: normal,
// lengths, plane tolerance), made at the face's first test of the pass and read by its others.
// On bench_peers' contact frames a face in contact meets about three faces of the other body,
// and computing both triangles' planes (two square roots and divisions in a chain) was most of
// a test that ends at the first plane. A pass owns it: begin_pass() before the pass's tests.
class FaceGeometryCache {
 public:
  // Sizes the cache for `faces` faces and forgets every entry.
  void reset(std::size_t faces) {
    geometry_.assign(faces, collision::TriangleGeometry{});
    stamps_.assign(faces, 0u);
    pass_ = 0;
  }
  // A new pass: every entry is stale. `shared`: tests run on several threads.
  void begin_pass(bool shared) {
    shared_ = shared;
    if (++pass_ == kBusy) {  // the stamps wrap: none may look current
      std::fill(stamps_.begin(), stamps_.end(), 0u);
      pass_ = 1;
    }
  }

  // Face `face`'s geometry this pass (the vertices of `f` at `positions`): the cached entry, or
  // one made now and kept. With several threads, one thread fills an entry (it marks it busy,
  // writes it, then publishes its stamp), the others use a copy of their own in `own`
  // meanwhile: the same bits either way.
  const collision::TriangleGeometry& get(std::uint32_t face, const gpu::Face& f,
                                         collision::VertexPositions positions,
                                         collision::TriangleGeometry& own) {
    if (!shared_) {
      if (stamps_[face] != pass_) {
        geometry_[face] = make(f, positions);
        stamps_[face] = pass_;
      }
      return geometry_[face];
    }
    std::atomic_ref<std::uint32_t> stamp(stamps_[face]);
    if (stamp.load(std::memory_order_acquire) == pass_) return geometry_[face];
    own = make(f, positions);
    std::uint32_t seen = stamp.load(std::memory_order_relaxed);
    if (seen != pass_ && seen != kBusy &&
        stamp.compare_exchange_strong(seen, kBusy, std::memory_order_acquire)) {
      geometry_[face] = own;
      stamp.store(pass_, std::memory_order_release);
    }
    return own;
  }

 private:
  static constexpr std::uint32_t kBusy = 0xFFFFFFFFu;

  static collision::TriangleGeometry make(const gpu::Face& f,
                                          collision::VertexPositions positions) {
    glm::vec3 t[3];
    collision::face_vertices(positions, f, t);
    return collision::triangle_geometry(t);
  }

  std::vector<collision::TriangleGeometry> geometry_;
  std::vector<std::uint32_t> stamps_;  // per face: the pass its entry was made in, 0: none
  std::uint32_t pass_ = 0;
  bool shared_ = false;
};

// The exact test of one face pair over the positions of the current pass
// (collision::face_pair_intersect: faces sharing an edge are neighbours, not a contact; faces
// sharing a node must meet elsewhere too). Face pairs are ordered, face_a < face_b: in a pair
// of bodies face_a is the lower-numbered body's, and within one body (self-collision, which
// broad phases enumerate both ways) the other order is skipped here, before it is counted.
struct NarrowPhase {
  collision::VertexPositions positions;
  const gpu::Face* faces;
  std::uint32_t* flags;         // per face: 1 when it intersects a face
  FaceGeometryCache* geometry;  // faces of two bodies are tested from it
  // The broad phase hands on only pairs whose triangles' boxes touch (the bvh's leaf boxes are
  // the min/max of the triangles' floats): the triangle test skips its box test.
  bool boxes_touch = false;

  // test() for a batch of pairs: queues the pair, and tests the batch when it is full. The
  // caller flushes the batch at the end. Faces of two bodies take the triangle test in two
  // loops: the first step (tri_tri_plane_step) over the whole batch without branches, keeping
  // the pairs it does not answer, then the rest of the test for those (boxes_touch must hold).
  void add(std::uint32_t face_a, std::uint32_t face_b, CandidateBatch& batch,
           ThreadPairs& out) const {
    if (face_a >= face_b) return;
    batch.face_a[batch.count] = face_a;
    batch.face_b[batch.count] = face_b;
    if (++batch.count == CandidateBatch::kSize) flush(batch, out);
  }

  void flush(CandidateBatch& batch, ThreadPairs& out) const {
    if (out.own.size() < 2 * CandidateBatch::kSize) out.own.resize(2 * CandidateBatch::kSize);
    collision::TriTriPlaneStep steps[CandidateBatch::kSize];
    std::uint32_t of_step[CandidateBatch::kSize];
    std::uint32_t kept = 0;
    for (std::uint32_t k = 0; k < batch.count; ++k) {
      const std::uint32_t face_a = batch.face_a[k];
      const std::uint32_t face_b = batch.face_b[k];
      const gpu::Face& fa = faces[face_a];
      const gpu::Face& fb = faces[face_b];
      if (fa.body == fb.body) {
        test(face_a, face_b, out);
        continue;
      }
      ++out.candidates;
      const collision::TriangleGeometry& ga = geometry->get(face_a, fa, positions, out.own[2 * k]);
      const collision::TriangleGeometry& gb =
          geometry->get(face_b, fb, positions, out.own[2 * k + 1]);
      of_step[kept] = k;
      kept += collision::tri_tri_plane_step(ga, gb, steps[kept]) ? 1u : 0u;
    }
    for (std::uint32_t s = 0; s < kept; ++s) {
      const collision::TriTriResult hit = collision::tri_tri_finish(steps[s]);
      if (hit.intersect) record(batch.face_a[of_step[s]], batch.face_b[of_step[s]], hit, out);
    }
    batch.count = 0;
  }

  // Tests the pair and appends it to `out` when the faces intersect; counts the test.
  void test(std::uint32_t face_a, std::uint32_t face_b, ThreadPairs& out) const {
    if (face_a >= face_b) return;
    ++out.candidates;
    const gpu::Face& fa = faces[face_a];
    const gpu::Face& fb = faces[face_b];
    collision::TriTriResult hit;
    if (fa.body != fb.body) {
      // What face_pair_intersect does for faces of two bodies (they share no node).
      collision::TriangleGeometry own_a;
      collision::TriangleGeometry own_b;
      const collision::TriangleGeometry& ga = geometry->get(face_a, fa, positions, own_a);
      const collision::TriangleGeometry& gb = geometry->get(face_b, fb, positions, own_b);
      hit = boxes_touch ? collision::tri_tri_intersect_touching(ga, gb)
                        : collision::tri_tri_intersect(ga, gb);
    } else {
      hit = collision::face_pair_intersect(fa, fb, positions);
    }
    if (hit.intersect) record(face_a, face_b, hit, out);
  }

  // An intersecting pair: its faces flagged, the pair appended to `out`.
  void record(std::uint32_t face_a, std::uint32_t face_b, const collision::TriTriResult& hit,
              ThreadPairs& out) const {
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
