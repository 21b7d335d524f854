#pragma once
// Loading models: a TetGen prefix, or a surface file tetrahedralized on the fly when the tool is
// built with TetGen.

#include <filesystem>

#include "deformcd/mesh.h"
#include "deformcd/tetrahedralize_options.h"

namespace deformcd::app {

/// A scene's model, a surface meshed with `meshing` (a scene's MeshingLoader).
[[nodiscard]] TetMesh load_scene_model(const std::filesystem::path& path,
                                       const TetrahedralizeOptions& meshing);

/// A MODEL argument (`info`): a surface is meshed as a scene meshes it by default
/// (default_scene_meshing()), so that `info` shows the body a scene would get.
[[nodiscard]] TetMesh load_model_argument(const std::filesystem::path& path);

}  // namespace deformcd::app
