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
  explicit CgalContestant(const std::vector<CollisionMesh>& meshes)
      : meshes_{meshes[0], meshes[1]} {}

  std::size_t detect(const FramePositions& positions) override {
    std::vector<Kernel::Triangle_3> triangles[2];
    std::vector<Box> boxes[2];
    for (int m = 0; m < 2; ++m) {
      const std::vector<glm::vec3>& p = positions[m];
      const auto point = [&](std::uint32_t v) { return Kernel::Point_3(p[v].x, p[v].y, p[v].z); };
      triangles[m].reserve(meshes_[m].triangles.size());
      boxes[m].reserve(meshes_[m].triangles.size());
      for (const Triangle& t : meshes_[m].triangles) {
        triangles[m].emplace_back(point(t[0]), point(t[1]), point(t[2]));
        boxes[m].emplace_back(triangles[m].back().bbox(),
                              static_cast<std::uint32_t>(triangles[m].size() - 1));
      }
    }
    std::size_t found = 0;
    CGAL::box_intersection_d(
        boxes[0].begin(), boxes[0].end(), boxes[1].begin(), boxes[1].end(),
        [&](const Box& a, const Box& b) {
          if (CGAL::do_intersect(triangles[0][a.info()], triangles[1][b.info()])) ++found;
        });
    return found;
  }

 private:
  CollisionMesh meshes_[2];
};

}  // namespace

std::unique_ptr<PeerContestant> make_cgal_contestant(const std::vector<CollisionMesh>& meshes) {
  return std::make_unique<CgalContestant>(meshes);
}

}  // namespace deformcd::bench
