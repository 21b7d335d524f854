#include <algorithm>
#include <string>

#include "deformcd/error.h"
#include "io/surface_formats.h"

namespace deformcd::io {

SurfaceBuilder::SurfaceBuilder(std::string file, unsigned index_base) {
  parsed_.source.vertex_file = file;
  parsed_.source.element_file = std::move(file);
  parsed_.source.index_base = index_base;
}

void SurfaceBuilder::reserve(std::uint64_t vertices, std::uint64_t polygons,
                             std::size_t file_size) {
  // Even a binary vertex takes 3 bytes and a polygon 4 (a count and three 1-byte indices).
  const auto vertex_room =
      static_cast<std::size_t>(std::min<std::uint64_t>(vertices, file_size / 3));
  const auto triangle_room =
      static_cast<std::size_t>(std::min<std::uint64_t>(polygons, file_size / 4));
  parsed_.mesh.vertices.reserve(vertex_room);
  parsed_.source.vertex_lines.reserve(vertex_room);
  parsed_.mesh.triangles.reserve(triangle_room);
  parsed_.source.element_lines.reserve(triangle_room);
}

void SurfaceBuilder::add_vertex(const glm::dvec3& position, std::size_t line) {
  parsed_.mesh.vertices.push_back(position);
  parsed_.source.vertex_lines.push_back(line);
}

void SurfaceBuilder::add_polygon(std::span<const std::int64_t> corners, std::size_t polygon,
                                 std::size_t line) {
  const MeshSource& src = parsed_.source;
  auto name = [&] { return "face " + std::to_string(polygon + src.index_base); };
  if (corners.size() < 3) {
    throw InputError(src.element_file, line,
                     name() + " has " + std::to_string(corners.size()) +
                         (corners.size() == 1 ? " corner" : " corners") +
                         "; a face needs at least 3");
  }
  const auto count = static_cast<std::int64_t>(vertex_count());
  for (const std::int64_t corner : corners) {
    if (corner < 0 || corner >= count) {
      const std::string valid = count == 0 ? "there are no vertices"
                                           : "valid: " + std::to_string(src.index_base) + ".." +
                                                 std::to_string(count - 1 + src.index_base);
      throw InputError(src.element_file, line,
                       name() + " refers to vertex " + std::to_string(corner + src.index_base) +
                           ", out of range (" + valid + ")");
    }
  }
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
    add_triangle({static_cast<std::uint32_t>(corners[0]), static_cast<std::uint32_t>(corners[k]),
                  static_cast<std::uint32_t>(corners[k + 1])},
                 line);
  }
}

void SurfaceBuilder::add_triangle(const Triangle& triangle, std::size_t line) {
  parsed_.mesh.triangles.push_back(triangle);
  parsed_.source.element_lines.push_back(line);
}

ParsedSurface SurfaceBuilder::finish() && {
  return std::move(parsed_);
}

}  // namespace deformcd::io
