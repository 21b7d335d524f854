#pragma once
// What a surface must be before TetGen -Y gets it: one closed, manifold, outward-oriented
// triangle surface with no degenerate triangle and no self-intersection.

#include <cstddef>
#include <string>

#include "cgal_types.h"

namespace make_models {

struct SurfaceReport {
  std::size_t vertices = 0;
  std::size_t faces = 0;
  std::size_t border_edges = 0;           // edges with only one triangle: holes
  std::size_t components = 0;             // connected components (by shared edges)
  std::size_t non_manifold_vertices = 0;  // vertices whose umbrella is not one disc
  std::size_t degenerate_faces = 0;       // collinear (zero-area) triangles
  bool self_intersecting = false;
  bool outward = false;            // meaningful for a closed surface only
  long genus = 0;                  // from Euler's formula, for one closed component
  double min_angle_degrees = 0.0;  // smallest triangle angle: TetGen -Y dislikes slivers
};

/// Measures everything SurfaceReport holds. Self-intersection tests are O(F log F).
SurfaceReport inspect(const Mesh& mesh);

/// True when the report describes a surface TetGen -Y can take.
bool is_clean(const SurfaceReport& report);

/// One line: "V=.. F=.. genus=.. ..." plus the problems found.
std::string describe(const SurfaceReport& report);

/// Throws deformcd::Error "<stage>: <problems>" unless the surface is clean.
void require_clean(const Mesh& mesh, const std::string& stage);

}  // namespace make_models
