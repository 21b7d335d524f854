#pragma once
// `deformcd bench`'s intersection census (deformcd/world_intersections.h) of scenes with a
// contact response: every measured frame, after its timed stages, the intersecting triangle
// pairs between bodies and within each body, the surface vertices inside another body, and the
// tetrahedra turned inside out (a body crushed where its surface folds through itself);
// reported per frame in the JSON and summed up in one line of the table.

#include <cstdint>
#include <memory>
#include <ostream>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "deformcd/intersection_census.h"
#include "deformcd/simulation_state.h"
#include "deformcd/world.h"

namespace deformcd {
class WorldIntersections;
}

namespace deformcd::app {

/// Counts a world's intersections frame by frame when it has a contact response.
class BenchIntersections {
 public:
  /// Over `world`, made from `bodies` (both must outlive this).
  BenchIntersections(const World& world, const std::vector<BodyInit>& bodies);
  ~BenchIntersections();
  /// Appends the census of the world's positions now to `per_frame`, and its inverted
  /// tetrahedra to `inverted` (nothing without response).
  void record(std::vector<IntersectionCensus>& per_frame, std::vector<std::uint64_t>& inverted);

 private:
  const std::vector<BodyInit>& bodies_;
  std::unique_ptr<WorldIntersections> census_;
};

/// The tetrahedra of `bodies` turned inside out at `positions` (one array per body): signed
/// volume <= 0, where the bodies were built positively oriented (Body::tetrahedra).
[[nodiscard]] std::uint64_t inverted_tetrahedra(
    const std::vector<std::vector<glm::vec3>>& positions, const std::vector<BodyInit>& bodies);

/// Adds "intersecting_pairs_between", "intersecting_pairs_self", "inside_vertices" and
/// "inverted_tetrahedra" (one per frame) to a method's per_frame JSON, when there is a census.
void add_intersection_fields(nlohmann::json& per_frame,
                             const std::vector<IntersectionCensus>& census,
                             const std::vector<std::uint64_t>& inverted);

/// One line: frames with any intersection or inside vertex, and the most in one frame (with
/// the most tetrahedra inverted).
void print_intersection_summary(std::ostream& out, const std::vector<IntersectionCensus>& census,
                                const std::vector<std::uint64_t>& inverted);

}  // namespace deformcd::app
