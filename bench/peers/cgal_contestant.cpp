// CGAL: box_intersection_d (a streamed segment tree) over the two bodies' face boxes, then the
// exact-predicate do_intersect on each candidate's Triangle_3 (Epick).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <memory>

#include "peer_contestants.h"

namespace deformcd::bench {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::uint32_t>;

class CgalContestant final : public PeerContestant {
 public:
  explicit CgalContestant(const WorldState& state) : state_(state) {}

  std::size_t detect(const std::vector<glm::vec4>& positions) override {
    std::vector<Kernel::Triangle_3> triangles(state_.faces.size());
    std::vector<Box> boxes[2];
    for (int b = 0; b < 2; ++b) {
      const gpu::ObjectInfo& o = state_.objects[b];
      boxes[b].reserve(o.face_count);
      for (std::uint32_t f = o.face_offset; f < o.face_offset + o.face_count; ++f) {
        const gpu::Face& face = state_.faces[f];
        const auto point = [&](std::uint32_t n) {
          return Kernel::Point_3(positions[n].x, positions[n].y, positions[n].z);
        };
        triangles[f] = Kernel::Triangle_3(point(face.a), point(face.b), point(face.c));
        boxes[b].emplace_back(triangles[f].bbox(), f);
      }
    }
    std::size_t found = 0;
    CGAL::box_intersection_d(boxes[0].begin(), boxes[0].end(), boxes[1].begin(), boxes[1].end(),
                             [&](const Box& a, const Box& b) {
                               if (CGAL::do_intersect(triangles[a.info()], triangles[b.info()]))
                                 ++found;
                             });
    return found;
  }

 private:
  const WorldState& state_;
};

}  // namespace

std::unique_ptr<PeerContestant> make_cgal_contestant(const WorldState& state) {
  return std::make_unique<CgalContestant>(state);
}

}  // namespace deformcd::bench
