#pragma once
/// \file world_intersections.h
/// The intersection census (deformcd/intersection_census.h) of a World's bodies: each body's
/// surface a mesh, at the world's current positions. For tests and `deformcd bench`.
///
///     deformcd::WorldIntersections census(world);
///     world.step();
///     deformcd::IntersectionCensus c = census.count();  // the frame just stepped

#include <glm/vec3.hpp>

#include <vector>

#include "deformcd/intersection_census.h"
#include "deformcd/world.h"

namespace deformcd {

/// The intersection census of a World's bodies, each body's surface a mesh: an
/// IntersectionCounter over the world's surfaces, fed the world's positions on each count().
class WorldIntersections {
 public:
  /// Over `world`'s bodies (it must outlive this); `threads` as IntersectionCounter's.
  explicit WorldIntersections(const World& world, int threads = 1);
  /// The census on the world's positions now (read back from the backend).
  [[nodiscard]] IntersectionCensus count();
  /// The positions the last count() read, one array per body (empty before the first): for
  /// more measures of the same frame without reading the positions back again.
  [[nodiscard]] const std::vector<std::vector<glm::vec3>>& positions() const { return positions_; }

 private:
  const World& world_;
  IntersectionCounter counter_;
  std::vector<std::vector<glm::vec3>> positions_;
};

}  // namespace deformcd
