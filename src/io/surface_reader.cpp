// read_surface: picks the reader by extension and validates what it returns.
//
// Why not Assimp: its importers build meshes for rendering, so the OBJ importer expands every
// face corner into a vertex of its own (24 vertices for an 8-vertex cube), and even with
// aiProcess_JoinIdenticalVertices the merged vertices come in corner order, not file order;
// TetGen's -Y mode and users' per-vertex data rely on the file's vertex order. It also reports
// errors without a line number ("OBJ: vertex index out of range"), and its OFF importer accepts
// a face index past the last vertex without an error. (Checked with Assimp 5.2.5; its OFF and
// PLY importers do keep the file's vertices and order.)

#include <algorithm>
#include <cctype>
#include <string>

#include "deformcd/error.h"
#include "deformcd/io.h"
#include "deformcd/mesh_validation.h"
#include "surface_formats.h"

namespace deformcd {

namespace {

std::string lowercase_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

bool is_surface_file(const std::filesystem::path& file) {
  const std::string ext = lowercase_extension(file);
  return ext == ".off" || ext == ".obj" || ext == ".stl" || ext == ".ply";
}

SurfaceMesh read_surface(const std::filesystem::path& file) {
  const std::string ext = lowercase_extension(file);
  io::ParsedSurface parsed;
  if (ext == ".off") {
    parsed = io::read_off(file);
  } else if (ext == ".obj") {
    parsed = io::read_obj(file);
  } else if (ext == ".stl") {
    parsed = io::read_stl(file);
  } else if (ext == ".ply") {
    parsed = io::read_ply(file);
  } else {
    throw InputError(file.string(),
                     "unknown surface format '" + ext + "' (expected .off, .obj, .stl or .ply)");
  }
  validate_surface_mesh(parsed.mesh, parsed.source);
  return std::move(parsed.mesh);
}

}  // namespace deformcd
