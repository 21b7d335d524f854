#pragma once
/// \file tetrahedralize_options.h
/// How a surface is filled with tetrahedra (TetGen's switches). A plain struct, so that scenes
/// can carry it without depending on the optional, AGPL-3 deformcd::tetgen target that acts on
/// it (tetrahedralize.h).

#include <optional>

namespace deformcd {

/// TetGen settings. Unset options leave TetGen's behaviour alone.
struct TetrahedralizeOptions {
  /// Radius-edge ratio bound (TetGen -q); TetGen's default bound is 2.0, smaller is finer.
  std::optional<double> quality;
  /// Maximum tetrahedron volume (TetGen -a), in the mesh's units cubed.
  std::optional<double> max_volume;
  /// Keep the surface exactly (TetGen -Y): the input vertices are the first nodes, in input
  /// order, and the boundary faces are exactly the input triangles.
  bool preserve_surface = false;
};

}  // namespace deformcd
