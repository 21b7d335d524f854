#include "model_input.h"

#include "deformcd/error.h"
#include "deformcd/io.h"
#ifdef DEFORMCD_HAS_TETGEN
#include "deformcd/tetrahedralize.h"
#endif

namespace deformcd::app {

TetMesh load_model_argument(const std::filesystem::path& path) {
#ifdef DEFORMCD_HAS_TETGEN
  return load_model(path);
#else
  if (is_surface_file(path)) {
    throw InputError(path.string(),
                     "is a surface mesh, and this deformcd was built without TetGen "
                     "(-DDEFORMCD_WITH_TETGEN=OFF): give a TetGen .node/.ele prefix instead");
  }
  return read_tetgen(path);
#endif
}

}  // namespace deformcd::app
