#include "deformcd/io.h"
#include "deformcd/tetrahedralize.h"

namespace deformcd {

TetMesh load_model(const std::filesystem::path& path, const TetrahedralizeOptions& options) {
  if (is_surface_file(path)) return tetrahedralize(read_surface(path), options, path.string());
  return read_tetgen(path);
}

}  // namespace deformcd
