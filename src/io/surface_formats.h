#pragma once
// The surface-format readers behind read_surface, and the builder they share so that every
// format triangulates polygons and reports bad indices the same way.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "deformcd/mesh.h"
#include "deformcd/mesh_validation.h"

namespace deformcd::io {

/// A surface as parsed, not yet validated, with where each vertex and triangle came from.
struct ParsedSurface {
  SurfaceMesh mesh;
  MeshSource source;
};

/// Collects vertices and polygons while a file is parsed. Line numbers are 1-based, or 0 where
/// the format has no lines (binary files).
class SurfaceBuilder {
 public:
  /// `index_base` is the file's first vertex index (OBJ: 1), used in messages only.
  SurfaceBuilder(std::string file, unsigned index_base);

  /// Reserves for up to the given counts, capped so that a corrupt header cannot exhaust memory.
  void reserve(std::uint64_t vertices, std::uint64_t polygons, std::size_t file_size);

  void add_vertex(const glm::dvec3& position, std::size_t line);

  /// Adds polygon number `polygon` (0-based), with 0-based `corners`, as the fan of triangles
  /// (c0, ck, ck+1). Throws InputError at `line` when it has fewer than 3 corners or a corner
  /// is not a vertex added so far. Degenerate triangles are left to validation.
  void add_polygon(std::span<const std::int64_t> corners, std::size_t polygon, std::size_t line);

  /// Adds one triangle of existing vertices, unchecked (validation checks it).
  void add_triangle(const Triangle& triangle, std::size_t line);

  [[nodiscard]] std::size_t vertex_count() const { return parsed_.mesh.vertices.size(); }
  [[nodiscard]] const std::string& file() const { return parsed_.source.vertex_file; }

  [[nodiscard]] ParsedSurface finish() &&;

 private:
  ParsedSurface parsed_;
};

// Each reader parses one format strictly from the file's contents, throwing InputError with
// `file` (the name for messages) and, for text, the line; none validates geometry,
// parse_surface does.
ParsedSurface read_off(std::string_view text, const std::string& file);
ParsedSurface read_stl(std::string_view data, const std::string& file);
/// Refuses an STL whose first 84 bytes (`head`) and size already show it is neither binary (its
/// triangle count disagrees with `size`) nor ASCII (no "solid", or control bytes): what read_stl
/// would say, without reading the rest of the file. Throws InputError.
void check_stl_size(std::string_view head, std::uint64_t size, const std::string& file);
ParsedSurface read_ply(std::string_view data, const std::string& file);
ParsedSurface read_obj(std::string_view text, const std::string& file);

enum class SurfaceFormat : std::uint8_t { kOff, kObj, kStl, kPly };

/// The format `file`'s extension names (any case), if read_surface knows it.
[[nodiscard]] std::optional<SurfaceFormat> surface_format_of(const std::filesystem::path& file);

/// write_off's contents: the mesh as OFF text. Throws Error as write_off does.
[[nodiscard]] std::string off_text(const SurfaceMesh& mesh);

/// read_surface on contents already in memory (the fuzz targets' entry point): parses `data`
/// as `format` and validates the mesh. Errors name `file`.
[[nodiscard]] SurfaceMesh parse_surface(std::string_view data, SurfaceFormat format,
                                        const std::string& file);

}  // namespace deformcd::io
