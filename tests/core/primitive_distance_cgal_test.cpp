// primitive_distance and closing_speed (src/core/collision/primitive_distance.h) against CGAL's
// squared_distance in double precision on the same float coordinates: vertex-triangle and
// segment-segment distances on random, near-touching, crossing, parallel and sliver
// configurations agree to float rounding, and no straight motion of the vertices closes a
// distance faster than closing_speed says (the proximity search and the contact response drop
// or leave asleep the pairs that bound says cannot come within reach).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/collision/primitive_distance.h"
#include "support/tri_tri_zone.h"

namespace deformcd::collision {
namespace {

using test::CgalKernel;
using test::to_cgal;

// CGAL's distance between the pair's primitives, in double.
double cgal_distance(std::uint32_t kind, const glm::vec3 x[4]) {
  if (kind == gpu::kContactEdgeEdge) {
    return std::sqrt(CGAL::to_double(
        CGAL::squared_distance(CgalKernel::Segment_3(to_cgal(x[0]), to_cgal(x[1])),
                               CgalKernel::Segment_3(to_cgal(x[2]), to_cgal(x[3])))));
  }
  return std::sqrt(CGAL::to_double(CGAL::squared_distance(
      to_cgal(x[0]), CgalKernel::Triangle_3(to_cgal(x[1]), to_cgal(x[2]), to_cgal(x[3])))));
}

// Random configurations of one of five shapes, each coordinate within a unit cube.
struct Configurations {
  std::mt19937 rng{20261201u};
  std::uniform_real_distribution<float> unit{-1.0f, 1.0f};

  glm::vec3 point() { return {unit(rng), unit(rng), unit(rng)}; }

  void next(std::uint32_t kind, int shape, glm::vec3 x[4]) {
    for (int k = 0; k < 4; ++k)
      x[k] = point();
    const float tiny = 1e-3f * (unit(rng) + 1.0f);
    if (shape == 1) {
      // Near touching: the first primitive a tiny step off a point of the second.
      const glm::vec3 target =
          kind == gpu::kContactEdgeEdge ? 0.5f * (x[2] + x[3]) : (x[1] + x[2] + x[3]) / 3.0f;
      const glm::vec3 offset = target - x[0] + tiny * point();
      x[0] += offset;
      if (kind == gpu::kContactEdgeEdge) x[1] += offset;
    } else if (shape == 2) {
      // Crossing or coplanar: everything in the plane z = 0.
      for (int k = 0; k < 4; ++k)
        x[k].z = 0.0f;
    } else if (shape == 3) {
      // Parallel: the second primitive's edge along the first's direction.
      const glm::vec3 along = x[1] - x[0];
      x[3] = x[2] + along * (0.5f + 0.5f * unit(rng));
    } else if (shape == 4) {
      // Sliver: the triangle (or second segment) nearly degenerate.
      x[3] = x[2] + tiny * point();
    }
  }
};

TEST(PrimitiveDistance, AgreesWithCgal) {
  Configurations c;
  for (const std::uint32_t kind : {gpu::kContactVertexFace, gpu::kContactEdgeEdge}) {
    double worst = 0.0;
    for (int i = 0; i < 200000; ++i) {
      glm::vec3 x[4];
      c.next(kind, i % 5, x);
      const double exact = cgal_distance(kind, x);
      const float ours = primitive_distance(kind, x);
      // Computed in double from the float coordinates, then rounded to float: within a few
      // float roundings of the configuration's size (3.5 at most).
      const double error = static_cast<double>(ours) - exact;
      worst = std::max(worst, std::abs(error));
      ASSERT_LT(std::abs(error), 1e-6)
          << "kind " << kind << ", case " << i << ": " << ours << " vs " << exact;
    }
    EXPECT_LT(worst, 1e-6) << "kind " << kind;
    RecordProperty(kind == gpu::kContactEdgeEdge ? "edge_edge_worst" : "vertex_face_worst",
                   std::to_string(worst));
  }
}

// Along straight motions, the exact distance at 33 moments never falls below the start's
// distance less the moment's share of closing_speed (up to rounding: 1e-6 of the size).
TEST(PrimitiveDistance, ClosingSpeedBoundsStraightMotions) {
  Configurations c;
  std::uniform_real_distribution<float> speed(0.0f, 2.0f);
  for (const std::uint32_t kind : {gpu::kContactVertexFace, gpu::kContactEdgeEdge}) {
    for (int i = 0; i < 20000; ++i) {
      glm::vec3 x[4], m[4];
      c.next(kind, i % 5, x);
      // A common motion (which closes nothing) plus each vertex's own.
      const glm::vec3 common = speed(c.rng) * c.point();
      for (int k = 0; k < 4; ++k)
        m[k] = common + 0.3f * speed(c.rng) * c.point();
      const double start = primitive_distance(kind, x);
      const double bound = closing_speed(kind, m);
      for (int s = 0; s <= 32; ++s) {
        const float tau = static_cast<float>(s) / 32.0f;
        glm::vec3 y[4];
        for (int k = 0; k < 4; ++k)
          y[k] = x[k] + tau * m[k];
        ASSERT_GE(cgal_distance(kind, y), start - tau * bound - 1e-6)
            << "kind " << kind << ", case " << i << ", tau " << tau;
      }
    }
  }
}

}  // namespace
}  // namespace deformcd::collision
