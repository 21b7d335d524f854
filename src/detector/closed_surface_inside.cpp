#include "detector/closed_surface_inside.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace deformcd::collision {

namespace {

// Shewchuk's machine epsilon (half an ulp of 1 in double) and the error bounds of his
// orient2d and orient3d without the adaptive stages ("Adaptive Precision Floating-Point
// Arithmetic and Fast Robust Geometric Predicates", 1997): a determinant larger than the bound
// has the sign of the exact one. Float coordinates convert to double exactly.
constexpr double kEpsilon = 1.0 / 9007199254740992.0;  // 2^-53
constexpr double kOrient2dBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEpsilon) * kEpsilon;

// +1, -1, or 0 when the filter cannot certify the sign.
int certified_sign(double det, double bound) {
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return 0;
}

// The sign of (a - c) x (b - c) in the plane: + when a, b, c turn counter-clockwise.
int orient2d(double ax, double ay, double bx, double by, double cx, double cy) {
  const double left = (ax - cx) * (by - cy);
  const double right = (ay - cy) * (bx - cx);
  return certified_sign(left - right, kOrient2dBound * (std::abs(left) + std::abs(right)));
}

// The sign of det[a - d; b - d; c - d] = ((b - a) x (c - a)) . (a - d).
int orient3d(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d) {
  const glm::dvec3 ad = a - d, bd = b - d, cd = c - d;
  const double bdxcdy = bd.x * cd.y, cdxbdy = cd.x * bd.y;
  const double cdxady = cd.x * ad.y, adxcdy = ad.x * cd.y;
  const double adxbdy = ad.x * bd.y, bdxady = bd.x * ad.y;
  const double det = ad.z * (bdxcdy - cdxbdy) + bd.z * (cdxady - adxcdy) + cd.z * (adxbdy - bdxady);
  const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(ad.z) +
                           (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bd.z) +
                           (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cd.z);
  return certified_sign(det, kOrient3dBound * permanent);
}

// The squared distance from p to triangle (a, b, c): Ericson's closest point by Voronoi regions
// ("Real-Time Collision Detection", 5.1.5).
double point_triangle_distance2(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                const glm::dvec3& c) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const auto squared = [&](const glm::dvec3& x) { return glm::dot(p - x, p - x); };
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return squared(a);
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return squared(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return squared(a + ab * (d1 / (d1 - d3)));
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return squared(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return squared(a + ac * (d2 / (d2 - d6)));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return squared(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
  const double denominator = va + vb + vc;
  if (!(denominator > 0.0)) return std::min(squared(a), std::min(squared(b), squared(c)));
  return squared(a + ab * (vb / denominator) + ac * (vc / denominator));
}

}  // namespace

std::vector<std::uint32_t> surface_vertices(std::span<const Triangle> triangles) {
  std::vector<std::uint32_t> corners;
  corners.reserve(3 * triangles.size());
  for (const Triangle& t : triangles)
    corners.insert(corners.end(), t.begin(), t.end());
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  return corners;
}

bool surface_closed(std::span<const Triangle> triangles) {
  // Each directed edge once, and its reverse once: every edge in exactly two triangles.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const Triangle& t : triangles)
    for (int e = 0; e < 3; ++e)
      if (++directed[{t[e], t[(e + 1) % 3]}] > 1) return false;
  for (const auto& [edge, uses] : directed)
    if (directed.find({edge.second, edge.first}) == directed.end()) return false;
  return !triangles.empty();
}

ClosedSurfaceInside::ClosedSurfaceInside(std::span<const glm::vec3> positions,
                                         std::span<const Triangle> triangles)
    : positions_(positions), triangles_(triangles) {
  lo_ = glm::vec3(std::numeric_limits<float>::max());
  hi_ = glm::vec3(-std::numeric_limits<float>::max());
  for (const Triangle& t : triangles_)
    for (const std::uint32_t v : t) {
      lo_ = glm::min(lo_, positions_[v]);
      hi_ = glm::max(hi_, positions_[v]);
    }
  // About two triangles a cell on a surface that covers its box's (y, z) face twice over.
  cells_ = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(triangles_.size()))), 1, 256);
  cell_y_ = std::max((hi_.y - lo_.y) / static_cast<float>(cells_), 1e-30f);
  cell_z_ = std::max((hi_.z - lo_.z) / static_cast<float>(cells_), 1e-30f);
  grid_.assign(static_cast<std::size_t>(cells_) * static_cast<std::size_t>(cells_), {});
  // The same monotone map for a triangle's box ends and for a point, so that a triangle whose
  // box holds the point's (y, z) is listed in the point's cell.
  const auto cell = [&](float x, float lo, float size) {
    return std::clamp(static_cast<int>(std::floor((x - lo) / size)), 0, cells_ - 1);
  };
  for (std::uint32_t f = 0; f < triangles_.size(); ++f) {
    const Triangle& t = triangles_[f];
    const glm::vec3 a = positions_[t[0]], b = positions_[t[1]], c = positions_[t[2]];
    const glm::vec3 lo = glm::min(glm::min(a, b), c), hi = glm::max(glm::max(a, b), c);
    for (int j = cell(lo.y, lo_.y, cell_y_); j <= cell(hi.y, lo_.y, cell_y_); ++j)
      for (int k = cell(lo.z, lo_.z, cell_z_); k <= cell(hi.z, lo_.z, cell_z_); ++k)
        grid_[grid_index(j, k)].push_back(f);
  }
}

bool ClosedSurfaceInside::inside(const glm::vec3& p) const {
  for (int axis = 0; axis < 3; ++axis)
    if (!(lo_[axis] <= p[axis] && p[axis] <= hi_[axis])) return false;
  const auto cell = [&](float x, float lo, float size) {
    return std::clamp(static_cast<int>(std::floor((x - lo) / size)), 0, cells_ - 1);
  };
  const std::vector<std::uint32_t>& along_x =
      grid_[grid_index(cell(p.y, lo_.y, cell_y_), cell(p.z, lo_.z, cell_z_))];
  for (int direction = 0; direction < 6; ++direction) {
    const int axis = direction / 2;
    const Parity parity = ray_parity(p, axis, direction % 2 == 0, axis == 0 ? &along_x : nullptr);
    if (parity != Parity::kUncertain) return parity == Parity::kInside;
  }
  // Every direction met the surface within rounding. On it (within 1e-7 of the box's diagonal:
  // at a vertex, on an edge), the winding number means nothing (it is the share of directions
  // pointing inside) and the point counts as not inside; elsewhere it decides.
  ++winding_fallbacks_;
  const double diagonal = glm::length(glm::dvec3(hi_) - glm::dvec3(lo_));
  if (distance_to_surface(p) <= 1e-7 * diagonal) return false;
  return std::abs(winding_number(p)) > 0.5;
}

ClosedSurfaceInside::Parity ClosedSurfaceInside::ray_parity(
    const glm::vec3& p, int axis, bool positive,
    const std::vector<std::uint32_t>* candidates) const {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;  // (u, v, axis) right-handed
  const glm::dvec3 q(p);
  bool odd = false;
  const std::size_t count = candidates != nullptr ? candidates->size() : triangles_.size();
  for (std::size_t i = 0; i < count; ++i) {
    const Triangle& t = triangles_[candidates != nullptr ? (*candidates)[i] : i];
    const glm::vec3 a = positions_[t[0]], b = positions_[t[1]], c = positions_[t[2]];
    // Exact float rejections: the triangle's box misses the ray.
    if (std::max(std::max(a[u], b[u]), c[u]) < p[u] || std::min(std::min(a[u], b[u]), c[u]) > p[u])
      continue;
    if (std::max(std::max(a[v], b[v]), c[v]) < p[v] || std::min(std::min(a[v], b[v]), c[v]) > p[v])
      continue;
    if (positive ? std::max(std::max(a[axis], b[axis]), c[axis]) < p[axis]
                 : std::min(std::min(a[axis], b[axis]), c[axis]) > p[axis])
      continue;
    // Where the ray's line meets the triangle's projection along the axis: each edge's side.
    const int s0 = orient2d(a[u], a[v], b[u], b[v], p[u], p[v]);
    const int s1 = orient2d(b[u], b[v], c[u], c[v], p[u], p[v]);
    const int s2 = orient2d(c[u], c[v], a[u], a[v], p[u], p[v]);
    const bool has_positive = s0 > 0 || s1 > 0 || s2 > 0;
    const bool has_negative = s0 < 0 || s1 < 0 || s2 < 0;
    if (has_positive && has_negative) continue;                    // surely outside the projection
    if (s0 == 0 || s1 == 0 || s2 == 0) return Parity::kUncertain;  // near an edge or a corner
    // Strictly inside the projection, whose orientation (the sign of the normal's axis
    // component) is s0: the ray crosses the plane ahead of p when the orientation of (a, b, c,
    // p), the sign of normal . (a - p), is that of the normal's component along the ray.
    const int side = orient3d(glm::dvec3(a), glm::dvec3(b), glm::dvec3(c), q);
    if (side == 0) return Parity::kUncertain;  // on the plane, within rounding
    if (side == (positive ? s0 : -s0)) odd = !odd;
  }
  return odd ? Parity::kInside : Parity::kOutside;
}

double ClosedSurfaceInside::distance_to_surface(const glm::vec3& p) const {
  double nearest2 = std::numeric_limits<double>::infinity();
  const glm::dvec3 q(p);
  for (const Triangle& t : triangles_)
    nearest2 = std::min(nearest2, point_triangle_distance2(q, glm::dvec3(positions_[t[0]]),
                                                           glm::dvec3(positions_[t[1]]),
                                                           glm::dvec3(positions_[t[2]])));
  return std::sqrt(nearest2);
}

double ClosedSurfaceInside::winding_number(const glm::vec3& p) const {
  // Van Oosterom and Strackee's solid angle of each triangle seen from p, summed over 4 pi.
  const glm::dvec3 q(p);
  double total = 0.0;
  for (const Triangle& t : triangles_) {
    const glm::dvec3 a = glm::dvec3(positions_[t[0]]) - q, b = glm::dvec3(positions_[t[1]]) - q,
                     c = glm::dvec3(positions_[t[2]]) - q;
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double numerator = glm::dot(a, glm::cross(b, c));
    const double denominator =
        la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * std::numbers::pi);
}

}  // namespace deformcd::collision
