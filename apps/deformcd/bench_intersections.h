#pragma once
// `deformcd bench`'s intersection census (deformcd/world_intersections.h) of scenes with a
// contact response: every measured frame, after its timed stages, the intersecting triangle
// pairs between bodies and within each body and the surface vertices inside another body;
// reported per frame in the JSON and summed up in one line of the table.

#include <cstdint>
#include <memory>
#include <ostream>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "deformcd/intersection_census.h"
#include "deformcd/world.h"

namespace deformcd {
class WorldIntersections;
}

namespace deformcd::app {

/// Counts a world's intersections frame by frame when it has a contact response.
class BenchIntersections {
 public:
  explicit BenchIntersections(const World& world);
  ~BenchIntersections();
  /// Appends the census of the world's positions now to `per_frame` (nothing without response).
  void record(std::vector<IntersectionCensus>& per_frame);

 private:
  std::unique_ptr<WorldIntersections> census_;
};

/// Adds "intersecting_pairs_between", "intersecting_pairs_self" and "inside_vertices" (one per
/// frame) to a method's per_frame JSON, when there is a census.
void add_intersection_fields(nlohmann::json& per_frame,
                             const std::vector<IntersectionCensus>& census);

/// One line: frames with any intersection or inside vertex, and the most in one frame.
void print_intersection_summary(std::ostream& out, const std::vector<IntersectionCensus>& census);

}  // namespace deformcd::app
