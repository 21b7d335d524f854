#pragma once
// Whether points are inside a closed triangle surface, for the intersection census
// (deformcd/intersection_census.h): ray parity, decided by orientation signs that a forward
// error bound certifies (Shewchuk's static filters, in double on float coordinates), so a
// decision is never a rounding's. A ray that passes too near an edge, a vertex or the plane of a
// triangle it crosses to be certain is given up for the next of six axis directions; a point for
// which all six are uncertain (on the surface, within rounding) takes the generalized winding
// number, inside when above one half, unless it is on the surface (within 1e-7 of the box's
// diagonal), which is not inside. Internal to deformcd_collision.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "deformcd/mesh.h"

namespace deformcd::collision {

/// Whether every edge of `triangles` is in exactly two of them, once each way (a closed,
/// consistently oriented surface; orientation does not matter to the parity, but a surface that
/// is not closed has no inside).
[[nodiscard]] bool surface_closed(std::span<const Triangle> triangles);

/// The surface's vertices (the corners of its triangles), ascending, each once.
[[nodiscard]] std::vector<std::uint32_t> surface_vertices(std::span<const Triangle> triangles);

/// One closed surface at one set of positions, with a grid over its triangles' boxes seen
/// along x (the first ray direction), built once per positions.
class ClosedSurfaceInside {
 public:
  /// `positions` and `triangles` must stay alive and unchanged while inside() is called.
  ClosedSurfaceInside(std::span<const glm::vec3> positions, std::span<const Triangle> triangles);

  /// Whether `p` is strictly inside the surface's box and then inside the surface (see above).
  [[nodiscard]] bool inside(const glm::vec3& p) const;
  /// Points for which no ray direction was certain and the winding number decided, so far.
  [[nodiscard]] std::uint64_t winding_fallbacks() const { return winding_fallbacks_; }

 private:
  enum class Parity { kOutside, kInside, kUncertain };
  /// The parity of the ray from p along axis `axis`, towards + when `positive`; over the
  /// triangles `candidates` (all of them when null).
  [[nodiscard]] Parity ray_parity(const glm::vec3& p, int axis, bool positive,
                                  const std::vector<std::uint32_t>* candidates) const;
  [[nodiscard]] double distance_to_surface(const glm::vec3& p) const;
  /// The grid list of cell (j, k) (0 <= j, k < cells_), its index computed in size_t.
  [[nodiscard]] std::size_t grid_index(int j, int k) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(cells_) +
           static_cast<std::size_t>(k);
  }
  [[nodiscard]] double winding_number(const glm::vec3& p) const;

  std::span<const glm::vec3> positions_;
  std::span<const Triangle> triangles_;
  glm::vec3 lo_{0.0f}, hi_{0.0f};
  // The grid over (y, z): cells_ x cells_ lists of the triangles whose box reaches the cell.
  int cells_ = 1;
  float cell_y_ = 1.0f, cell_z_ = 1.0f;
  std::vector<std::vector<std::uint32_t>> grid_;
  mutable std::uint64_t winding_fallbacks_ = 0;
};

}  // namespace deformcd::collision
