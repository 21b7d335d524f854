#pragma once
// The header of a PLY file (http://paulbourke.net/dataformats/ply/): its encoding and the
// elements, each with a count and typed scalar or list properties, that the body then holds.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace deformcd::io {

enum class PlyType : std::uint8_t {
  kInt8,
  kUInt8,
  kInt16,
  kUInt16,
  kInt32,
  kUInt32,
  kFloat32,
  kFloat64
};

[[nodiscard]] std::size_t size_of(PlyType type);
[[nodiscard]] bool is_integer(PlyType type);

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;   ///< the value's type, or the list items' type
  std::optional<PlyType> list_count;  ///< the type of the list's length, for list properties
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
  std::size_t line = 0;  ///< the header line declaring it
};

enum class PlyEncoding : std::uint8_t { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::kAscii;
  std::vector<PlyElement> elements;
  std::size_t body_offset = 0;      ///< first byte after the "end_header" line
  std::size_t body_first_line = 0;  ///< line number of the body's first line (ASCII)
};

/// Parses the header at the start of `data`. Throws InputError with `file` and the line.
[[nodiscard]] PlyHeader parse_ply_header(std::string_view data, const std::string& file);

/// Checks the elements' counts against the body's size before anything is reserved for them:
/// a binary element takes at least its scalars' and list counts' bytes, an ASCII one a line
/// (at least 2 bytes). Throws InputError at the line of the first element that cannot fit.
void check_ply_counts(const PlyHeader& header, std::size_t file_size, const std::string& file);

}  // namespace deformcd::io
