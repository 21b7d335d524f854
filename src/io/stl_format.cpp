// STL, ASCII and binary, read by hand.
// Binary: an 80-byte header, a little-endian uint32 triangle count n, then n records of 50 bytes
// (normal and 3 corners as 12 little-endian floats, a uint16 attribute). Binary is recognised by
// its size, 84 + 50 n, not by the header: many binary files begin with "solid" too.
// ASCII: solid [name] / facet normal nx ny nz / outer loop / vertex x y z (x3) / endloop /
// endfacet / ... / endsolid [name], keywords in any case, several solids allowed.
// STL stores corners, not shared vertices: exactly equal corners are welded into one vertex,
// numbered in order of first appearance, so the result is the same on every run.

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>

#include "deformcd/error.h"
#include "io/byte_reader.h"
#include "io/surface_formats.h"
#include "io/text_scanner.h"

namespace deformcd::io {

namespace {

constexpr std::size_t kBinaryHeader = 84;
constexpr std::size_t kBinaryTriangle = 50;

struct CornerHash {
  std::size_t operator()(const glm::dvec3& p) const {
    std::uint64_t h = 0;
    for (int k = 0; k < 3; ++k) {
      h = (h ^ std::bit_cast<std::uint64_t>(p[k])) * 0x100000001b3ull;  // FNV-style mixing
      h ^= h >> 29;
    }
    return static_cast<std::size_t>(h);
  }
};

// Maps each distinct corner position to a vertex of the builder.
class CornerWelder {
 public:
  explicit CornerWelder(SurfaceBuilder& builder) : builder_(builder) {}

  std::uint32_t vertex_of(glm::dvec3 corner, std::size_t line) {
    corner += glm::dvec3(0.0);  // -0.0 + 0.0 == +0.0: equal doubles must hash equally
    const auto [it, inserted] =
        index_.try_emplace(corner, static_cast<std::uint32_t>(builder_.vertex_count()));
    if (inserted) builder_.add_vertex(corner, line);
    return it->second;
  }

 private:
  SurfaceBuilder& builder_;
  std::unordered_map<glm::dvec3, std::uint32_t, CornerHash> index_;
};

bool is_finite(const glm::dvec3& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const char x = a[i] >= 'A' && a[i] <= 'Z' ? static_cast<char>(a[i] - 'A' + 'a') : a[i];
    if (x != b[i]) return false;
  }
  return true;
}

// Text STL holds no control characters; binary float data nearly always does (0.0f, 1.0f...).
bool looks_like_text(std::string_view data) {
  for (const char c : data) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x09 || (u > 0x0d && u < 0x20) || u == 0x7f) return false;
  }
  return true;
}

bool starts_with_solid(std::string_view data) {
  const std::size_t first = data.find_first_not_of(" \t\r\n");
  return first != std::string_view::npos && data.size() - first >= 5 &&
         equals_ignoring_case(data.substr(first, 5), "solid");
}

ParsedSurface read_binary(std::string_view data, const std::string& file) {
  ByteReader bytes(data, 80, false);
  const auto count = bytes.read<std::uint32_t>();
  SurfaceBuilder builder(file, 0);
  builder.reserve(count, count, data.size());
  CornerWelder welder(builder);
  for (std::uint32_t t = 0; t < count; ++t) {
    bytes.skip(12);  // the normal: recomputed from the corners wherever needed
    Triangle triangle{};
    for (std::uint32_t& vertex : triangle) {
      glm::dvec3 corner;
      for (int k = 0; k < 3; ++k) {
        corner[k] = static_cast<double>(bytes.read<float>());
      }
      if (!is_finite(corner)) {
        throw InputError(file, "triangle " + std::to_string(t) + " (at byte " +
                                   std::to_string(kBinaryHeader + t * kBinaryTriangle) +
                                   ") has a NaN or infinite coordinate");
      }
      vertex = welder.vertex_of(corner, 0);
    }
    bytes.skip(2);  // attribute byte count
    builder.add_triangle(triangle, 0);
  }
  return std::move(builder).finish();
}

// "endloop" or "vertex ...": what a record starts with, for messages.
std::string opening(const TextScanner& in) {
  return std::string(in.token(0)) + (in.size() > 1 ? " ..." : "");
}

// Reads the next record and checks that it is `keyword` followed by `values` more tokens.
void expect(TextScanner& in, std::string_view keyword, std::size_t values, const char* form) {
  if (!in.next_record()) in.fail_at_end("expected '" + std::string(form) + "', file ends");
  if (!equals_ignoring_case(in.token(0), keyword) || in.size() != 1 + values) {
    in.fail("expected '" + std::string(form) + "', found '" + opening(in) + "'");
  }
}

ParsedSurface read_ascii(std::string_view text, const std::string& file) {
  TextScanner in(text, file, /*hash_comments=*/false);
  SurfaceBuilder builder(file, 0);
  CornerWelder welder(builder);
  in.next_record();  // "solid [name]", checked by the caller
  for (;;) {
    if (!in.next_record()) in.fail_at_end("expected 'facet' or 'endsolid', file ends");
    if (equals_ignoring_case(in.token(0), "endsolid")) {
      if (!in.next_record()) break;
      if (!equals_ignoring_case(in.token(0), "solid")) {
        in.fail("expected 'solid' or the end of the file after 'endsolid', found '" +
                std::string(in.token(0)) + "'");
      }
      continue;
    }
    if (!equals_ignoring_case(in.token(0), "facet") || in.size() != 5 ||
        !equals_ignoring_case(in.token(1), "normal")) {
      in.fail("expected 'facet normal <nx> <ny> <nz>' or 'endsolid', found '" + opening(in) + "'");
    }
    for (std::size_t k = 2; k < 5; ++k) {
      (void)in.real(k);  // the normal: checked, not used
    }
    const std::size_t facet_line = in.line();
    expect(in, "outer", 1, "outer loop");
    if (!equals_ignoring_case(in.token(1), "loop")) in.fail("expected 'outer loop'");
    Triangle triangle{};
    for (std::uint32_t& vertex : triangle) {
      expect(in, "vertex", 3, "vertex <x> <y> <z>");
      const glm::dvec3 corner(in.real(1), in.real(2), in.real(3));
      if (!is_finite(corner)) in.fail("vertex has a NaN or infinite coordinate");
      vertex = welder.vertex_of(corner, in.line());
    }
    expect(in, "endloop", 0, "endloop");
    expect(in, "endfacet", 0, "endfacet");
    builder.add_triangle(triangle, facet_line);
  }
  return std::move(builder).finish();
}

}  // namespace

void check_stl_size(std::string_view head, std::uint64_t size, const std::string& file) {
  if (size < kBinaryHeader || head.size() < kBinaryHeader) return;
  const auto count = ByteReader(head, 80, false).read<std::uint32_t>();
  const std::uint64_t expected = kBinaryHeader + std::uint64_t{count} * kBinaryTriangle;
  if (size == expected) return;
  if (!starts_with_solid(head) || !looks_like_text(head)) {
    throw InputError(file, "binary STL header announces " + std::to_string(count) + " triangles (" +
                               std::to_string(expected) + " bytes), but the file has " +
                               std::to_string(size) + " bytes: truncated or not an STL file");
  }
}

ParsedSurface read_stl(std::string_view data, const std::string& file) {
  const std::string& name = file;
  if (data.size() >= kBinaryHeader) {
    check_stl_size(data.substr(0, kBinaryHeader), data.size(), name);
    const auto count = ByteReader(data, 80, false).read<std::uint32_t>();
    if (data.size() == kBinaryHeader + std::uint64_t{count} * kBinaryTriangle) {
      return read_binary(data, name);
    }
    if (!looks_like_text(data)) check_stl_size(data, data.size(), name);  // the same message
  } else if (!starts_with_solid(data)) {
    throw InputError(name,
                     "is neither ASCII STL (does not start with 'solid') nor binary STL "
                     "(shorter than the 84-byte header)");
  }
  return read_ascii(data, name);
}

}  // namespace deformcd::io
