// The intersection census's inside test (src/detector/closed_surface_inside.h) against CGAL's
// Side_of_triangle_mesh with exact predicates, on a real model's closed surface: random points
// through its box, and points a hair off its faces and at its vertices, where a rounding
// decision would go wrong.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <cstdint>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "deformcd/body.h"
#include "deformcd/io.h"
#include "detector/closed_surface_inside.h"

namespace deformcd {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

struct Surface {
  std::vector<glm::vec3> positions;
  std::vector<Triangle> triangles;
};

Surface model_surface(const std::string& name) {
  const Body body =
      build_body(read_tetgen(std::string(DEFORMCD_SOURCE_DIR) + "/assets/models/" + name));
  Surface s;
  for (const glm::vec4& p : body.positions)
    s.positions.emplace_back(p);
  for (const gpu::Face& f : body.faces)
    s.triangles.push_back({f.a, f.b, f.c});
  return s;
}

Kernel::Point_3 point(const glm::vec3& p) {
  return {static_cast<double>(p.x), static_cast<double>(p.y), static_cast<double>(p.z)};
}

void expect_agreement(const std::string& model) {
  const Surface s = model_surface(model);
  ASSERT_TRUE(collision::surface_closed(s.triangles)) << model;
  Mesh mesh;
  std::vector<Mesh::Vertex_index> vertices;
  for (const glm::vec3& p : s.positions)
    vertices.push_back(mesh.add_vertex(point(p)));
  for (const Triangle& t : s.triangles)
    mesh.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]);
  const CGAL::Side_of_triangle_mesh<Mesh, Kernel> oracle(mesh);
  const collision::ClosedSurfaceInside inside(s.positions, s.triangles);

  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : s.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const float size = glm::length(hi - lo);
  std::mt19937 random(33);
  std::vector<glm::vec3> points;
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < 20000; ++i)  // through the box and a little beyond
    points.push_back(lo - 0.05f * (hi - lo) +
                     1.1f * (hi - lo) * glm::vec3(unit(random), unit(random), unit(random)));
  std::uniform_real_distribution<float> offset(-1.0f, 1.0f);
  for (const Triangle& t : s.triangles) {  // centroids a hair either side, the corners
    const glm::vec3 a = s.positions[t[0]], b = s.positions[t[1]], c = s.positions[t[2]];
    const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
    const glm::vec3 centre = (a + b + c) / 3.0f;
    points.push_back(centre + 1e-6f * size * n);
    points.push_back(centre - 1e-6f * size * n);
    points.push_back(a + 1e-6f * size * glm::vec3(offset(random), offset(random), offset(random)));
    points.push_back(a);
  }
  std::uint64_t inside_count = 0, boundary = 0, disagreements = 0;
  for (const glm::vec3& p : points) {
    const CGAL::Bounded_side side = oracle(point(p));
    const bool expected = side == CGAL::ON_BOUNDED_SIDE;
    const bool got = inside.inside(p);
    if (side == CGAL::ON_BOUNDARY) ++boundary;
    if (expected) ++inside_count;
    if (got != expected) {
      ++disagreements;
      ADD_FAILURE() << model << ": point (" << p.x << ", " << p.y << ", " << p.z << "): CGAL says "
                    << (expected ? "inside" : "not inside");
      if (disagreements > 10) return;
    }
  }
  EXPECT_GT(inside_count, points.size() / 20) << model;  // the test saw both sides
  EXPECT_GT(boundary, 0u) << model;                      // and points on the surface
  std::cout << model << ": " << points.size() << " points, " << inside_count << " inside, "
            << boundary << " on the surface, " << inside.winding_fallbacks()
            << " decided by the winding number\n";
}

TEST(ClosedSurfaceInsideCgal, BunnyAgreesWithCgal) {
  expect_agreement("bunny");
}
TEST(ClosedSurfaceInsideCgal, ArmadilloAgreesWithCgal) {
  expect_agreement("armadillo");
}

}  // namespace
}  // namespace deformcd
