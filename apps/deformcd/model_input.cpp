#include "model_input.h"

#include <sstream>
#include <string>

#include "deformcd/error.h"
#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "progress.h"
#ifdef DEFORMCD_HAS_TETGEN
#include "deformcd/tetrahedralize.h"
#endif

namespace deformcd::app {

#ifdef DEFORMCD_HAS_TETGEN
namespace {

// TetGen's switches for `meshing`, e.g. "-pq2Y".
std::string tetgen_switches(const TetrahedralizeOptions& meshing) {
  std::ostringstream s;
  s << "-p";
  if (meshing.quality) s << 'q' << *meshing.quality;
  if (meshing.max_volume) s << 'a' << *meshing.max_volume;
  if (meshing.preserve_surface) s << 'Y';
  return s.str();
}

}  // namespace
#endif

TetMesh load_scene_model(const std::filesystem::path& path, const TetrahedralizeOptions& meshing) {
#ifdef DEFORMCD_HAS_TETGEN
  if (is_surface_file(path)) {
    status("tetrahedralizing " + path.string() + " (TetGen " + tetgen_switches(meshing) + ")");
  }
  return load_model(path, meshing);
#else
  (void)meshing;
  if (is_surface_file(path)) {
    throw InputError(path.string(),
                     "is a surface mesh, and this deformcd was built without TetGen "
                     "(-DDEFORMCD_WITH_TETGEN=OFF): give a TetGen .node/.ele prefix instead");
  }
  return read_tetgen(path);
#endif
}

TetMesh load_model_argument(const std::filesystem::path& path) {
  return load_scene_model(path, default_scene_meshing());
}

}  // namespace deformcd::app
