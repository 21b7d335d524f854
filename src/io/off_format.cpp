// OFF (Geomview's Object File Format), read and written by hand:
//   [ST][C][N]OFF [#vertices #faces [#edges]]
//   #vertices #faces [#edges]              (when not on the header line)
//   x y z [nx ny nz] [r g b [a]] [s t]     one line per vertex, extras as the prefixes say
//   n i1 ... in [color]                    one line per face, 0-based, optional color
// '#' comments and blank lines are allowed anywhere. The homogeneous (4OFF), n-dimensional
// (nOFF) and binary variants are rejected with a message saying so.

#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "deformcd/error.h"
#include "deformcd/io.h"
#include "io/atomic_file.h"
#include "io/surface_formats.h"
#include "io/text_scanner.h"
#include "io/text_writer.h"

namespace deformcd {

namespace io {

namespace {

// How many numbers follow x y z on a vertex line, as the header keyword's prefixes say.
struct VertexExtras {
  std::size_t min = 0;
  std::size_t max = 0;
};

VertexExtras parse_off_keyword(const TextScanner& in) {
  std::string_view keyword = in.token(0);
  VertexExtras extras;
  auto take = [&keyword](std::string_view prefix) {
    if (!keyword.starts_with(prefix)) return false;
    keyword.remove_prefix(prefix.size());
    return true;
  };
  auto add = [&extras](std::size_t min, std::size_t max) {
    extras.min += min;
    extras.max += max;
  };
  if (take("ST")) add(2, 2);  // texture coordinates
  if (take("C")) add(3, 4);   // color, RGB or RGBA
  if (take("N")) add(3, 3);   // normal
  if (keyword == "4OFF" || keyword == "nOFF" || keyword == "4nOFF") {
    in.fail("'" + std::string(in.token(0)) +
            "' (homogeneous or n-dimensional vertices) is not supported; use plain 3D OFF");
  }
  if (keyword != "OFF") {
    in.fail("expected the 'OFF' header, found '" + std::string(in.token(0)) + "'");
  }
  if (in.size() > 1 && in.token(1) == "BINARY") in.fail("binary OFF is not supported");
  return extras;
}

}  // namespace

ParsedSurface read_off(std::string_view text, const std::string& file) {
  TextScanner in(text, file);
  if (!in.next_record()) in.fail_at_end("is empty: expected the 'OFF' header");
  const VertexExtras extras = parse_off_keyword(in);

  // The counts may share the header line ("OFF 8 6 12") or follow it.
  std::size_t first = 1;
  if (in.size() == 1) {
    if (!in.next_record()) in.fail_at_end("expected '#vertices #faces #edges' after 'OFF'");
    first = 0;
  }
  const std::size_t count_fields = in.size() - first;
  if (count_fields < 2 || count_fields > 3) {
    in.fail("expected the counts '#vertices #faces #edges', found " + std::to_string(count_fields) +
            " values");
  }
  const auto vertex_count = in.integer<std::uint32_t>(first);
  const auto face_count = in.integer<std::uint32_t>(first + 1);
  if (count_fields == 3) (void)in.integer<std::uint64_t>(first + 2);  // edges: unused
  in.check_line_count(std::uint64_t{vertex_count} + face_count, "vertex or face",
                      "vertices and faces");

  SurfaceBuilder builder(file, 0);
  builder.reserve(vertex_count, face_count, text.size());
  for (std::uint32_t i = 0; i < vertex_count; ++i) {
    if (!in.next_record()) {
      in.fail_at_end("expected " + std::to_string(vertex_count) + " vertices, file ends after " +
                     std::to_string(i));
    }
    if (in.size() < 3 + extras.min || in.size() > 3 + extras.max) {
      const std::string expected = extras.max == 0 ? "3 coordinates"
                                   : extras.min == extras.max
                                       ? std::to_string(3 + extras.min) + " numbers"
                                       : std::to_string(3 + extras.min) + " to " +
                                             std::to_string(3 + extras.max) + " numbers";
      in.fail("expected " + expected + " for vertex " + std::to_string(i) + ", found " +
              std::to_string(in.size()));
    }
    builder.add_vertex({in.real(0), in.real(1), in.real(2)}, in.line());
    for (std::size_t k = 3; k < in.size(); ++k) {
      (void)in.real(k);
    }
  }

  std::vector<std::int64_t> corners;
  for (std::uint32_t f = 0; f < face_count; ++f) {
    if (!in.next_record()) {
      in.fail_at_end("expected " + std::to_string(face_count) + " faces, file ends after " +
                     std::to_string(f));
    }
    const auto n = in.integer<std::uint32_t>(0);
    // After the n indices, a face may carry a color: an index, RGB or RGBA.
    if (in.size() < 1 + std::size_t{n} || in.size() > 5 + std::size_t{n}) {
      in.fail("face " + std::to_string(f) + " declares " + std::to_string(n) +
              " vertices but the line has " + std::to_string(in.size() - 1) +
              " values after the count");
    }
    corners.clear();
    for (std::size_t k = 1; k <= n; ++k) {
      corners.push_back(in.integer<std::int64_t>(k));
    }
    for (std::size_t k = 1 + n; k < in.size(); ++k) {
      (void)in.real(k);
    }
    builder.add_polygon(corners, f, in.line());
  }
  if (in.next_record()) {
    in.fail("unexpected content after the " + std::to_string(face_count) + " declared faces");
  }
  return std::move(builder).finish();
}

std::string off_text(const SurfaceMesh& mesh) {
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const glm::dvec3& p = mesh.vertices[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      throw Error("write_off: vertex " + std::to_string(i) + " has a NaN or infinite coordinate");
    }
  }
  std::string out = "OFF\n";
  out.reserve(mesh.vertices.size() * 64 + mesh.triangles.size() * 32);
  append_integer(out, mesh.vertices.size());
  out += ' ';
  append_integer(out, mesh.triangles.size());
  out += " 0\n";
  for (const glm::dvec3& p : mesh.vertices) {
    for (int k = 0; k < 3; ++k) {
      if (k > 0) out += ' ';
      append_real(out, p[k]);
    }
    out += '\n';
  }
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    out += '3';
    for (const std::uint32_t v : mesh.triangles[i]) {
      if (v >= mesh.vertices.size()) {
        throw Error("write_off: triangle " + std::to_string(i) + " refers to vertex " +
                    std::to_string(v) + ", but the mesh has " +
                    std::to_string(mesh.vertices.size()) + " vertices");
      }
      out += ' ';
      append_integer(out, v);
    }
    out += '\n';
  }
  return out;
}

}  // namespace io

void write_off(const SurfaceMesh& mesh, const std::filesystem::path& file) {
  const io::FileContents contents[] = {{file, io::off_text(mesh)}};
  io::write_files_atomically(contents);
}

}  // namespace deformcd
