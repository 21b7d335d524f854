#pragma once
// Reading a source model and turning it into one closed, outward-oriented surface.

#include <cstddef>
#include <filesystem>

#include "cgal_types.h"
#include "surface_checks.h"

namespace make_models {

struct RepairSummary {
  std::size_t components_removed = 0;  // stray pieces dropped (only the largest is kept)
  std::size_t holes_filled = 0;
  std::size_t holes_unfaired = 0;  // filled, but the fairing system could not be solved
  std::size_t hole_faces_added = 0;
  std::size_t degenerate_faces_removed = 0;
  bool reversed = false;                     // faces flipped to point outward
  bool self_intersections_repaired = false;  // CGAL's local remeshing had to run
  SurfaceReport result;                      // the repaired surface, clean
};

/// Reads `file` (OFF, or anything CGAL::IO::read_polygon_soup reads) and repairs it: duplicated
/// and degenerate polygons removed, soup oriented and stitched into a mesh, only the largest
/// connected component kept, holes filled (refined and faired, so the patch blends with the
/// surrounding sampling), degenerate faces removed, outward orientation, and local repair of
/// self-intersections. Throws deformcd::InputError naming the file when it cannot be read or
/// repaired into a clean surface.
Mesh load_and_repair(const std::filesystem::path& file, RepairSummary& summary);

}  // namespace make_models
