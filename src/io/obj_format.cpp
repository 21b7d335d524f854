// Wavefront OBJ through tinyobjloader (Debian's libtinyobjloader, built with double precision),
// which keeps the file's vertex order and resolves v/vt/vn references, negative (relative) ones
// included. It is lax, so a strict scan of our own runs first. tinyobjloader 2.0.0rc10:
//  - reads a missing or non-numeric coordinate as 0 ("v 1 2", "v 1 2 abc") without a word;
//  - only warns about positive indices past the last vertex and keeps them, and silently
//    resolves negative ones past the first vertex to negative indices;
//  - reads "2x" as index 2 (atoi), and drops faces of fewer than 3 corners with a warning;
//  - parses decimals with its own routine, which is off by an ulp for about half of all
//    shortest round-trip doubles;
//  - gives error messages with a line but without the file, and stores a polygon's corner
//    count in an unsigned char.
// Our scan checks every 'v' and 'f' line (numbers, corner counts, index ranges, with file and
// line) and parses the coordinates itself with from_chars; tinyobjloader then supplies the
// polygons, whose number must match the scan's. Only whole-line '#' comments are allowed, as in
// tinyobjloader. Materials (mtllib) are not loaded.

// The imported target tinyobjloader::tinyobjloader_double defines TINYOBJLOADER_USE_DOUBLE (its
// ABI); the guard keeps the header's doubles if it ever stops doing so.
#ifndef TINYOBJLOADER_USE_DOUBLE
#define TINYOBJLOADER_USE_DOUBLE
#endif
#include <tiny_obj_loader.h>

#include <charconv>
#include <istream>
#include <streambuf>
#include <string>
#include <vector>

#include "deformcd/error.h"
#include "io/surface_formats.h"
#include "io/text_scanner.h"

namespace deformcd::io {

namespace {

// The file's text as an istream for tinyobjloader, without copying it. The buffer is never
// written through: std::streambuf only moves its pointers when reading, and putting back a
// character that differs from the one read (the only write) goes to pbackfail(), which fails.
class MemoryStreamBuf : public std::streambuf {
 public:
  explicit MemoryStreamBuf(std::string_view text) {
    char* begin = const_cast<char*>(text.data());
    setg(begin, begin, begin + text.size());
  }
};

// The largest polygon num_face_vertices (unsigned char) can describe.
constexpr std::size_t kMaxCorners = 255;

struct ObjScan {
  std::vector<glm::dvec3> vertices;
  std::vector<std::size_t> vertex_lines;
  std::vector<std::size_t> face_lines;
};

// True when `part` is an integer; empty parts are allowed where `may_be_empty`.
bool is_index(std::string_view part, bool may_be_empty) {
  std::int64_t ignored = 0;
  return part.empty() ? may_be_empty : parse_integer(part, ignored) == NumberParse::kOk;
}

// Checks one corner reference of face `face` (0-based): "v", "v/vt", "v//vn" or "v/vt/vn", and
// returns its vertex index as written. The vt and vn indices are left to tinyobjloader.
std::int64_t check_corner(const TextScanner& in, std::size_t k, std::size_t vertices_so_far,
                          std::size_t face) {
  const std::string_view token = in.token(k);
  std::string_view parts[3];
  std::size_t count = 0;
  for (std::size_t start = 0;; ++count) {
    const std::size_t slash = token.find('/', start);
    if (count < 3) parts[count] = token.substr(start, slash - start);
    if (slash == std::string_view::npos) break;
    start = slash + 1;
  }
  std::int64_t index = 0;
  const bool well_formed = count < 3 && parse_integer(parts[0], index) == NumberParse::kOk &&
                           (count < 1 || is_index(parts[1], count == 2)) &&
                           (count < 2 || is_index(parts[2], false));
  if (!well_formed) {
    in.fail("'" + std::string(token) + "' is not a vertex reference (v, v/vt, v//vn or v/vt/vn)");
  }
  auto name = [face] { return "face " + std::to_string(face + 1); };
  if (index == 0) in.fail(name() + " refers to vertex 0; OBJ indices start at 1");
  if (index < 0 && static_cast<std::uint64_t>(-index) > vertices_so_far) {
    in.fail(name() + " refers to vertex " + std::to_string(index) + ", but only " +
            std::to_string(vertices_so_far) + " vertices precede it");
  }
  return index;
}

ObjScan scan_obj(std::string_view text, const std::string& file) {
  TextScanner in(text, file, /*hash_comments=*/false);
  ObjScan scan;
  std::int64_t max_index = 0;  // largest positive index, checked once all vertices are known
  std::size_t max_index_line = 0, max_index_face = 0;
  while (in.next_record()) {
    const std::string_view keyword = in.token(0);
    if (keyword == "v") {
      if (in.size() < 4 || in.size() > 8) {
        in.fail("expected 3 coordinates after 'v' (then optionally w, or r g b), found " +
                std::to_string(in.size() - 1) + " values");
      }
      scan.vertices.emplace_back(in.real(1), in.real(2), in.real(3));
      for (std::size_t k = 4; k < in.size(); ++k) {
        (void)in.real(k);
      }
      scan.vertex_lines.push_back(in.line());
    } else if (keyword == "f") {
      const std::size_t face = scan.face_lines.size();
      if (in.size() < 4) {
        in.fail("face " + std::to_string(face + 1) + " has " + std::to_string(in.size() - 1) +
                " corners; a face needs at least 3");
      }
      if (in.size() - 1 > kMaxCorners) {
        in.fail("face " + std::to_string(face + 1) + " has more than " +
                std::to_string(kMaxCorners) + " corners (tinyobjloader's limit)");
      }
      for (std::size_t k = 1; k < in.size(); ++k) {
        const std::int64_t index = check_corner(in, k, scan.vertices.size(), face);
        if (index > max_index) {
          max_index = index;
          max_index_line = in.line();
          max_index_face = face;
        }
      }
      scan.face_lines.push_back(in.line());
    }
  }
  if (max_index > static_cast<std::int64_t>(scan.vertices.size())) {
    throw InputError(file, max_index_line,
                     "face " + std::to_string(max_index_face + 1) + " refers to vertex " +
                         std::to_string(max_index) + ", out of range (valid: 1.." +
                         std::to_string(scan.vertices.size()) + ")");
  }
  return scan;
}

// tinyobjloader's messages end in "line N.)": take N for our InputError (0 if absent).
std::size_t line_in_message(const std::string& message) {
  const std::size_t at = message.rfind("line ");
  if (at == std::string::npos) return 0;
  std::size_t line = 0;
  std::from_chars(message.data() + at + 5, message.data() + message.size(), line);
  return line;
}

}  // namespace

ParsedSurface read_obj(std::string_view text, const std::string& file) {
  const std::string& name = file;
  ObjScan scan = scan_obj(text, name);

  MemoryStreamBuf buffer(text);
  std::istream stream(&buffer);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warnings, errors;
  const bool loaded = tinyobj::LoadObj(&attrib, &shapes, &materials, &warnings, &errors, &stream,
                                       /*readMatFn=*/nullptr, /*triangulate=*/false);
  if (!loaded || !errors.empty()) {
    while (!errors.empty() && errors.back() == '\n') {
      errors.pop_back();
    }
    throw InputError(name, line_in_message(errors),
                     "tinyobjloader: " + (errors.empty() ? "cannot parse" : errors));
  }
  if (attrib.vertices.size() != 3 * scan.vertices.size()) {
    throw InputError(name, "tinyobjloader read " + std::to_string(attrib.vertices.size() / 3) +
                               " vertices where the file has " +
                               std::to_string(scan.vertices.size()) + " 'v' lines");
  }

  SurfaceBuilder builder(name, 1);
  builder.reserve(scan.vertices.size(), scan.face_lines.size(), text.size());
  for (std::size_t i = 0; i < scan.vertices.size(); ++i) {
    builder.add_vertex(scan.vertices[i], scan.vertex_lines[i]);
  }
  std::size_t loaded_faces = 0;
  for (const tinyobj::shape_t& shape : shapes) {
    loaded_faces += shape.mesh.num_face_vertices.size();
  }
  if (loaded_faces != scan.face_lines.size()) {
    throw InputError(name, "tinyobjloader read " + std::to_string(loaded_faces) +
                               " faces where the file has " +
                               std::to_string(scan.face_lines.size()) + " 'f' lines");
  }
  // tinyobjloader splits faces into shapes at 'g', 'o' and 'usemtl' lines, in file order.
  std::size_t face = 0;
  std::vector<std::int64_t> corners;
  for (const tinyobj::shape_t& shape : shapes) {
    std::size_t next = 0;
    for (const unsigned char n : shape.mesh.num_face_vertices) {
      corners.clear();
      for (std::size_t k = 0; k < n; ++k) {
        corners.push_back(shape.mesh.indices[next + k].vertex_index);
      }
      next += n;
      builder.add_polygon(corners, face, scan.face_lines[face]);
      ++face;
    }
  }
  return std::move(builder).finish();
}

}  // namespace deformcd::io
