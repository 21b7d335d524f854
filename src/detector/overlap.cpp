#include "deformcd/overlap.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "core/collision/bvh.h"
#include "core/collision/collision_data.h"
#include "core/collision/vertex_positions.h"
#include "deformcd/error.h"
#include "deformcd/gpu_layout.h"
#include "detector/closed_surface_inside.h"

namespace deformcd {

struct OverlapFinder::Impl {
  std::vector<CollisionMesh> meshes;
  std::vector<bool> closed;
  /// Per mesh: its surface vertices (its triangles' corners), ascending.
  std::vector<std::vector<std::uint32_t>> surface_vertices;
};

namespace {

void check_positions(const CollisionMesh& mesh, std::size_t index,
                     std::span<const glm::vec3> positions) {
  if (positions.size() != mesh.vertex_count)
    throw InputError("OverlapFinder::find", collision::mesh_label(index, mesh.name) + " has " +
                                                std::to_string(positions.size()) +
                                                " positions, expected " +
                                                std::to_string(mesh.vertex_count));
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const glm::vec3& p = positions[v];
    if (!std::isfinite(p.x + p.y + p.z))
      throw InputError("OverlapFinder::find", collision::mesh_label(index, mesh.name) + " vertex " +
                                                  std::to_string(v) + " has a non-finite position");
  }
}

glm::dvec3 corner(std::span<const glm::vec3> positions, std::uint32_t v) {
  return glm::dvec3(positions[v]);
}

/// Twice the triangle's vector area (its normal times twice its area, right-handed in its
/// corners' order).
glm::dvec3 area_vector(std::span<const glm::vec3> positions, const Triangle& t) {
  const glm::dvec3 p0 = corner(positions, t[0]);
  return glm::cross(corner(positions, t[1]) - p0, corner(positions, t[2]) - p0);
}

/// +1 when the closed surface's triangles wind outward (positive enclosed volume), else -1.
double orientation(std::span<const glm::vec3> positions, const std::vector<Triangle>& triangles) {
  double volume6 = 0.0;
  for (const Triangle& t : triangles)
    volume6 += glm::dot(corner(positions, t[0]), area_vector(positions, t));
  return volume6 < 0.0 ? -1.0 : 1.0;
}

/// The flux sum_t (corners of t inside / 3) x t's outward vector area (twice), over `mesh`'s
/// triangles, in their order; `weight` adds each term's length (for the scale of the sum).
glm::dvec3 inside_flux(std::span<const glm::vec3> positions, const std::vector<Triangle>& triangles,
                       const std::vector<std::uint8_t>& inside, double& weight) {
  const double sign = orientation(positions, triangles);
  glm::dvec3 flux(0.0);
  for (const Triangle& t : triangles) {
    const int corners = inside[t[0]] + inside[t[1]] + inside[t[2]];
    if (corners == 0) continue;
    const glm::dvec3 term = (sign * corners / 3.0) * area_vector(positions, t);
    flux += term;
    weight += glm::length(term);
  }
  return flux;
}

/// Per vertex of `mesh`, 1 for each of its surface vertices inside `container` (at their
/// positions); adds their number to `count`.
std::vector<std::uint8_t> inside_flags(const CollisionMesh& mesh,
                                       const std::vector<std::uint32_t>& surface_vertices,
                                       std::span<const glm::vec3> positions,
                                       const CollisionMesh& container,
                                       std::span<const glm::vec3> container_positions,
                                       std::size_t& count) {
  const collision::ClosedSurfaceInside surface(container_positions, container.triangles);
  std::vector<std::uint8_t> inside(mesh.vertex_count, 0u);
  for (const std::uint32_t v : surface_vertices) {
    inside[v] = surface.inside(positions[v]) ? 1u : 0u;
    count += inside[v];
  }
  return inside;
}

/// The container's triangles in a BVH at the given positions, for rays from inside it.
class RayTree {
 public:
  RayTree(std::span<const glm::vec3> positions, const std::vector<Triangle>& triangles)
      : positions_(positions), triangles_(triangles) {
    faces_.reserve(triangles.size());
    for (const Triangle& t : triangles)
      faces_.push_back({t[0], t[1], t[2], 0u});
    const collision::MeshVertices vertices{.data = &positions[0].x, .stride = 3u};
    nodes_ =
        collision::build_bvh(&vertices, faces_, 0u, static_cast<std::uint32_t>(faces_.size()), 0u);
    boxes_.resize(nodes_.size());
    collision::refit_bvh(nodes_, 0u, static_cast<std::uint32_t>(nodes_.size()), &vertices, faces_,
                         boxes_);
  }

  /// The triangle the ray from `origin` along unit `direction` meets first (the smaller index
  /// on a tie) and the distance to it; false when it meets none.
  bool first_hit(const glm::dvec3& origin, const glm::dvec3& direction, std::uint32_t& triangle,
                 double& distance) const {
    const glm::dvec3 inverse = 1.0 / direction;  // +-inf for a zero component: the slabs hold
    double best = std::numeric_limits<double>::infinity();
    std::uint32_t best_triangle = 0;
    std::uint32_t stack[collision::kBvhMaxDepth + 1];
    std::uint32_t size = 0;
    stack[size++] = 0u;
    while (size > 0) {
      const std::uint32_t i = stack[--size];
      if (!box_within(boxes_[i], origin, inverse, best)) continue;
      const gpu::BvhNode& n = nodes_[i];
      if (n.face == gpu::kBvhInternal) {
        stack[size++] = n.right;
        stack[size++] = n.left;
        continue;
      }
      double t = 0.0;
      if (ray_meets(origin, direction, triangles_[n.face], t) &&
          (t < best || (t == best && n.face < best_triangle))) {
        best = t;
        best_triangle = n.face;
      }
    }
    if (!std::isfinite(best)) return false;
    triangle = best_triangle;
    distance = best;
    return true;
  }

 private:
  // Whether the ray meets the box before `limit` (slab test; a box the ray starts in counts).
  static bool box_within(const gpu::Box& box, const glm::dvec3& origin, const glm::dvec3& inverse,
                         double limit) {
    double near = 0.0, far = limit;
    for (int axis = 0; axis < 3; ++axis) {
      double t0 = (box.min[axis] - origin[axis]) * inverse[axis];
      double t1 = (box.max[axis] - origin[axis]) * inverse[axis];
      if (std::isnan(t0) || std::isnan(t1)) {  // along the slab's plane, origin on it
        continue;
      }
      if (t0 > t1) std::swap(t0, t1);
      near = std::max(near, t0);
      far = std::min(far, t1);
      if (near > far) return false;
    }
    return true;
  }

  // Moller-Trumbore in double, the barycentric bounds widened by 1e-9 so that a ray through a
  // shared edge meets at least one of its triangles; t > 0 only.
  bool ray_meets(const glm::dvec3& origin, const glm::dvec3& direction, const Triangle& tri,
                 double& t) const {
    const glm::dvec3 p0 = corner(positions_, tri[0]);
    const glm::dvec3 e1 = corner(positions_, tri[1]) - p0;
    const glm::dvec3 e2 = corner(positions_, tri[2]) - p0;
    const glm::dvec3 h = glm::cross(direction, e2);
    const double det = glm::dot(e1, h);
    if (det == 0.0) return false;
    const double inverse = 1.0 / det;
    const glm::dvec3 s = origin - p0;
    const double u = glm::dot(s, h) * inverse;
    constexpr double kSlack = 1e-9;
    if (u < -kSlack || u > 1.0 + kSlack) return false;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(direction, q) * inverse;
    if (v < -kSlack || u + v > 1.0 + kSlack) return false;
    t = glm::dot(e2, q) * inverse;
    return t > 0.0;
  }

  std::span<const glm::vec3> positions_;
  const std::vector<Triangle>& triangles_;
  std::vector<gpu::Face> faces_;
  std::vector<gpu::BvhNode> nodes_;
  std::vector<gpu::Box> boxes_;
};

/// Each surface vertex of `mesh` flagged in `inside`, with the triangle of the container that
/// the ray from it along `direction` meets first.
std::vector<PenetratingVertex> leaving(const std::vector<std::uint32_t>& surface_vertices,
                                       const std::vector<std::uint8_t>& inside,
                                       std::span<const glm::vec3> positions,
                                       const RayTree& container, const glm::dvec3& direction) {
  std::vector<PenetratingVertex> out;
  for (const std::uint32_t v : surface_vertices) {
    if (inside[v] == 0u) continue;
    std::uint32_t triangle = 0;
    double distance = 0.0;
    if (!container.first_hit(glm::dvec3(positions[v]), direction, triangle, distance)) continue;
    out.push_back({.vertex = v, .triangle = triangle, .depth = static_cast<float>(distance)});
  }
  return out;
}

}  // namespace

OverlapFinder::OverlapFinder(std::vector<CollisionMesh> meshes) : impl_(std::make_unique<Impl>()) {
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const CollisionMesh& mesh = meshes[m];
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      for (const std::uint32_t v : mesh.triangles[t]) {
        if (v >= mesh.vertex_count)
          throw InputError(collision::mesh_label(m, mesh.name),
                           "triangle " + std::to_string(t) + " names vertex " + std::to_string(v) +
                               ", beyond its " + std::to_string(mesh.vertex_count) + " vertices");
      }
    }
    impl_->closed.push_back(!mesh.triangles.empty() && collision::surface_closed(mesh.triangles));
    impl_->surface_vertices.push_back(collision::surface_vertices(mesh.triangles));
  }
  impl_->meshes = std::move(meshes);
}

OverlapFinder::~OverlapFinder() = default;
OverlapFinder::OverlapFinder(OverlapFinder&&) noexcept = default;
OverlapFinder& OverlapFinder::operator=(OverlapFinder&&) noexcept = default;

std::size_t OverlapFinder::mesh_count() const {
  return impl_->meshes.size();
}

bool OverlapFinder::closed(std::size_t mesh) const {
  return impl_->closed.at(mesh);
}

Overlap OverlapFinder::find(std::size_t a, std::size_t b, std::span<const glm::vec3> a_positions,
                            std::span<const glm::vec3> b_positions) const {
  const std::size_t count = impl_->meshes.size();
  if (a >= count || b >= count || a == b)
    throw InputError("OverlapFinder::find", "meshes " + std::to_string(a) + " and " +
                                                std::to_string(b) + ": expected two different of " +
                                                std::to_string(count));
  const CollisionMesh& mesh_a = impl_->meshes[a];
  const CollisionMesh& mesh_b = impl_->meshes[b];
  check_positions(mesh_a, a, a_positions);
  check_positions(mesh_b, b, b_positions);
  Overlap overlap;
  if (!impl_->closed[a] || !impl_->closed[b]) return overlap;
  const std::vector<std::uint32_t>& surface_a = impl_->surface_vertices[a];
  const std::vector<std::uint32_t>& surface_b = impl_->surface_vertices[b];
  std::size_t inside = 0;
  const std::vector<std::uint8_t> a_inside =
      inside_flags(mesh_a, surface_a, a_positions, mesh_b, b_positions, inside);
  const std::vector<std::uint8_t> b_inside =
      inside_flags(mesh_b, surface_b, b_positions, mesh_a, a_positions, inside);
  if (inside == 0) return overlap;
  // The gradient of the shared volume V with a's translation t is dV/dt = the flux of a's
  // outward normals over a's surface inside b, = minus that of b's over b's surface inside a
  // (the two close the shared volume). Both estimate it; their difference uses every inside
  // vertex of both.
  double weight = 0.0;
  const glm::dvec3 flux = inside_flux(b_positions, mesh_b.triangles, b_inside, weight) -
                          inside_flux(a_positions, mesh_a.triangles, a_inside, weight);
  glm::dvec3 direction(0.0);
  if (glm::length(flux) > 1e-6 * weight) {
    direction = glm::normalize(flux);
  } else {
    glm::dvec3 centre_a(0.0), centre_b(0.0);
    for (const std::uint32_t v : surface_a)
      centre_a += corner(a_positions, v);
    for (const std::uint32_t v : surface_b)
      centre_b += corner(b_positions, v);
    const glm::dvec3 apart = centre_a / static_cast<double>(surface_a.size()) -
                             centre_b / static_cast<double>(surface_b.size());
    direction = glm::length(apart) > 0.0 ? glm::normalize(apart) : glm::dvec3(1.0, 0.0, 0.0);
  }
  overlap.direction = glm::vec3(direction);
  const RayTree tree_b(b_positions, mesh_b.triangles);
  overlap.a_in_b = leaving(surface_a, a_inside, a_positions, tree_b, direction);
  const RayTree tree_a(a_positions, mesh_a.triangles);
  overlap.b_in_a = leaving(surface_b, b_inside, b_positions, tree_a, -direction);
  return overlap;
}

}  // namespace deformcd
