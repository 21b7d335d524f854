#pragma once
// Placing a surface in the unit box and writing it so that every reader sees the same numbers.

#include <filesystem>

#include "cgal_types.h"

namespace make_models {

/// Micrometre grid of the normalized model (its largest extent is 1 m).
inline constexpr double kCoordinateGrid = 1e-6;

/// Centres the bounding box at the origin, scales uniformly so that the largest extent is 1,
/// and snaps every coordinate to kCoordinateGrid. The snapped value k * 1e-6 is computed as the
/// correctly rounded k / 1e6, the same double strtod returns for the printed "%.6f", so the
/// surface checked in memory is bit for bit the surface TetGen and deformcd read back.
void normalize_to_unit_box(Mesh& mesh);

/// Writes an OFF file with "%.6f" coordinates, vertices and faces in index order (call
/// collect_garbage() first). Throws deformcd::Error when the file cannot be written.
void write_off(const Mesh& mesh, const std::filesystem::path& file);

}  // namespace make_models
