// CGAL 5.5: box_intersection_d (a streamed segment tree) over the two bodies' triangle boxes,
// then the exact-predicate do_intersect on each candidate's Triangle_3 (Epick), set up as CGAL's
// own Polygon_mesh_processing does for two meshes (PMP::internal::compute_face_face_
// intersection, PMP/intersection.h):
//  - boxes Box_with_info_d<double, 3, triangle index, ID_FROM_BOX_ADDRESS>, and the algorithm
//    given pointers to them (it reorders its input; CGAL's comment: pointers are about 10 %
//    faster than copying the boxes), the box address being the box's id;
//  - cutoff 2000 (PMP's value; the algorithm's default, 10, is the row "cgal-cutoff10"): the
//    segment tree stops splitting below that many boxes and scans them;
//  - topology CLOSED (the default): boxes that only touch, and zero-width boxes of triangles
//    in a coordinate plane, are reported, since touching triangles intersect for every
//    contestant (HALF_OPEN would miss them);
//  - each candidate's two triangles made from the frame's float positions (exactly, in double).
// With Parallel_tag (CGAL linked with oneTBB), box_intersection_d splits both ranges in four and
// runs the 16 sub-intersections as TBB tasks on every core; the callback counts atomically.

#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <mutex>

#include "exact_triangle_test.h"
#include "peer_contestants.h"

namespace deformcd::bench {

namespace {

using Box =
    CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::uint32_t,
                                              CGAL::Box_intersection_d::ID_FROM_BOX_ADDRESS>;

template <typename ConcurrencyTag>
class CgalContestant final : public PeerContestant {
 public:
  CgalContestant(const std::vector<CollisionMesh>& meshes, std::ptrdiff_t cutoff)
      : meshes_{meshes[0], meshes[1]}, cutoff_(cutoff) {
    for (int m = 0; m < 2; ++m) {
      boxes_[m].resize(meshes_[m].triangles.size());
      pointers_[m].resize(meshes_[m].triangles.size());
    }
  }

  std::size_t detect(const FramePositions& positions, std::vector<FacePair>* pairs) override {
    for (int m = 0; m < 2; ++m) {
      const std::vector<glm::vec3>& p = positions[m];
      const std::vector<Triangle>& triangles = meshes_[m].triangles;
      for (std::size_t f = 0; f < triangles.size(); ++f) {
        const Triangle& t = triangles[f];
        double lo[3];
        double hi[3];
        for (int axis = 0; axis < 3; ++axis) {
          const float a = p[t[0]][axis];
          const float b = p[t[1]][axis];
          const float c = p[t[2]][axis];
          lo[axis] = std::min({a, b, c});
          hi[axis] = std::max({a, b, c});
        }
        boxes_[m][f] = Box(lo, hi, static_cast<std::uint32_t>(f));
        pointers_[m][f] = &boxes_[m][f];  // in order again: the last run reordered them
      }
    }
    std::atomic<std::size_t> found = 0;
    std::atomic<std::size_t> tested = 0;
    std::mutex record;
    CGAL::box_intersection_d<ConcurrencyTag>(
        pointers_[0].begin(), pointers_[0].end(), pointers_[1].begin(), pointers_[1].end(),
        [&](const Box* a, const Box* b) {
          tested.fetch_add(1, std::memory_order_relaxed);
          if (!exact_triangles_intersect(positions[0], meshes_[0].triangles[a->info()],
                                         positions[1], meshes_[1].triangles[b->info()]))
            return;
          found.fetch_add(1, std::memory_order_relaxed);
          if (pairs != nullptr) {
            const std::lock_guard<std::mutex> lock(record);
            pairs->emplace_back(a->info(), b->info());
          }
        },
        cutoff_);
    candidates_ = tested.load();
    return found.load();
  }

  [[nodiscard]] std::size_t candidates() const override { return candidates_; }

 private:
  CollisionMesh meshes_[2];
  std::ptrdiff_t cutoff_;
  std::size_t candidates_ = 0;
  std::vector<Box> boxes_[2];
  std::vector<const Box*> pointers_[2];
};

}  // namespace

std::unique_ptr<PeerContestant> make_cgal_contestant(const std::vector<CollisionMesh>& meshes,
                                                     std::ptrdiff_t cutoff, bool parallel) {
  if (parallel) return std::make_unique<CgalContestant<CGAL::Parallel_tag>>(meshes, cutoff);
  return std::make_unique<CgalContestant<CGAL::Sequential_tag>>(meshes, cutoff);
}

}  // namespace deformcd::bench
