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
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "deformcd/error.h"
#include "deformcd/io.h"
#include "deformcd/mesh_validation.h"
#include "io/surface_formats.h"
#include "io/text_scanner.h"

namespace deformcd {

namespace io {

std::optional<SurfaceFormat> surface_format_of(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".off") return SurfaceFormat::kOff;
  if (ext == ".obj") return SurfaceFormat::kObj;
  if (ext == ".stl") return SurfaceFormat::kStl;
  if (ext == ".ply") return SurfaceFormat::kPly;
  return std::nullopt;
}

SurfaceMesh parse_surface(std::string_view data, SurfaceFormat format, const std::string& file) {
  ParsedSurface parsed;
  switch (format) {
    case SurfaceFormat::kOff:
      parsed = read_off(data, file);
      break;
    case SurfaceFormat::kObj:
      parsed = read_obj(data, file);
      break;
    case SurfaceFormat::kStl:
      parsed = read_stl(data, file);
      break;
    case SurfaceFormat::kPly:
      parsed = read_ply(data, file);
      break;
  }
  validate_surface_mesh(parsed.mesh, parsed.source);
  return std::move(parsed.mesh);
}

}  // namespace io

namespace {

// A binary STL's size is in its 84-byte header: a file whose size disagrees (and that is no
// ASCII STL) is refused before it is read, whatever its size.
void check_stl_head(const std::filesystem::path& file) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (ec) return;  // read_whole_file says why
  std::ifstream in(file, std::ios::binary);
  std::string head(84, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  io::check_stl_size(head, size, file.string());
}

}  // namespace

bool is_surface_file(const std::filesystem::path& file) {
  return io::surface_format_of(file).has_value();
}

SurfaceMesh read_surface(const std::filesystem::path& file) {
  const std::optional<io::SurfaceFormat> format = io::surface_format_of(file);
  if (!format) {
    throw InputError(file.string(), "unknown surface format '" + file.extension().string() +
                                        "' (expected .off, .obj, .stl or .ply)");
  }
  if (*format == io::SurfaceFormat::kStl) check_stl_head(file);
  return io::parse_surface(io::read_whole_file(file), *format, file.string());
}

}  // namespace deformcd
