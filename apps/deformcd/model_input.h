#pragma once
// Loading a MODEL argument: a TetGen prefix, or a surface file tetrahedralized on the fly when
// the tool is built with TetGen.

#include <filesystem>

#include "deformcd/mesh.h"

namespace deformcd::app {

[[nodiscard]] TetMesh load_model_argument(const std::filesystem::path& path);

}  // namespace deformcd::app
