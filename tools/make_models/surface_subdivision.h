#pragma once
// Refining a surface that is too coarse for the requested face count, so that decimation can
// then bring it down to the exact count (the finer scaling models need more triangles than
// some of CGAL's source meshes have).

#include <cstddef>

#include "cgal_types.h"

namespace make_models {

/// Loop-subdivides `mesh` (each pass splits every triangle into four and smooths the vertices)
/// until it has at least `min_faces` triangles; does nothing when it already has them. Returns
/// the number of passes.
int subdivide_to_at_least(Mesh& mesh, std::size_t min_faces);

}  // namespace make_models
