#pragma once
// Edge-collapse decimation of a closed surface to an exact triangle count.

#include <cstddef>
#include <string>

#include "cgal_types.h"

namespace make_models {

enum class CollapsePolicy {
  lindstrom_turk,    // Lindstrom-Turk memoryless cost and placement
  garland_heckbert,  // Garland-Heckbert plane quadrics
};

/// Parses "lt" / "gh" (throws deformcd::Error otherwise).
CollapsePolicy parse_collapse_policy(const std::string& name);

/// Collapses edges until `mesh` has at most `target_faces` triangles. Every collapse of an
/// interior edge removes two triangles and three edges, so a closed mesh reaches an even target
/// exactly (when enough edges remain collapsible). Placements that would flip a triangle's
/// normal are refused. Returns the number of edges removed (CGAL's count: three per collapse).
std::size_t decimate(Mesh& mesh, std::size_t target_faces, CollapsePolicy policy);

}  // namespace make_models
