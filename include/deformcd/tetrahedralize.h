#pragma once
/// \file tetrahedralize.h
/// Surface -> tetrahedral mesh with TetGen, in process. Part of the optional deformcd::tetgen
/// target, which is AGPL-3 like TetGen itself: the core library never depends on it.

#include <filesystem>
#include <string>

#include "deformcd/mesh.h"
#include "deformcd/tetrahedralize_options.h"

namespace deformcd {

/// Checks that `surface` bounds a solid: closed (every edge in exactly two triangles),
/// consistently oriented, with no repeated triangle. Throws InputError naming `source` and the
/// offending edge or triangle. Self-intersections are left to TetGen (reported by
/// tetrahedralize).
void check_closed_surface(const SurfaceMesh& surface, const std::string& source);

/// Tetrahedralizes the solid bounded by `surface` (check_closed_surface first). TetGen's
/// failures (self-intersections, tiny features, out of memory) become InputError / Error naming
/// `source`; they never abort the process. The result is validated and positively oriented,
/// with `faces` holding the boundary triangles TetGen reports.
[[nodiscard]] TetMesh tetrahedralize(const SurfaceMesh& surface,
                                     const TetrahedralizeOptions& options = {},
                                     const std::string& source = "<surface>");

/// A model for a body: a TetGen prefix, or a surface file tetrahedralized with `options`. Its
/// signature is a scene's ModelLoader's, so `make_scene_bodies(scene, load_model, frames)`
/// meshes each surface model with its body's `meshing` (scene.h).
[[nodiscard]] TetMesh load_model(const std::filesystem::path& path,
                                 const TetrahedralizeOptions& options = {});

}  // namespace deformcd
