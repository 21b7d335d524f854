// PLY, ASCII and binary of either endianness, read by hand (Debian has no PLY library).
// The body is read element by element as the header declares, whatever the elements: the
// "vertex" element's x, y, z (any scalar type) become the vertices and the "face" element's
// vertex_indices (or vertex_index) list, of any count and index types, becomes polygons; every
// other property and element is read past. ASCII bodies hold one element per line.

#include <string>
#include <vector>

#include "deformcd/error.h"
#include "io/byte_reader.h"
#include "io/ply_header.h"
#include "io/surface_formats.h"
#include "io/text_scanner.h"

namespace deformcd::io {

namespace {

// ASCII values: one element per line, so that errors name the line.
class AsciiValues {
 public:
  AsciiValues(std::string_view body, const std::string& file, std::size_t first_line)
      : in_(body, file, /*hash_comments=*/false, first_line) {}

  void begin(const PlyElement& element, std::uint64_t i) {
    if (!in_.next_record()) {
      in_.fail_at_end("expected " + std::to_string(element.count) + " " + element.name +
                      " elements, file ends after " + std::to_string(i));
    }
    next_ = 0;
  }
  double real(PlyType) { return in_.real(take()); }
  std::int64_t integer(PlyType) { return in_.integer<std::int64_t>(take()); }
  void end(const PlyElement& element, std::uint64_t i) {
    if (next_ != in_.size()) {
      in_.fail(element.name + " " + std::to_string(i) + " has " + std::to_string(in_.size()) +
               " values, its properties declare " + std::to_string(next_));
    }
  }
  void finish() {
    if (in_.next_record()) in_.fail("unexpected content after the last element");
  }
  [[nodiscard]] std::size_t line() const { return in_.line(); }
  [[noreturn]] void fail(const std::string& message) const { in_.fail(message); }

 private:
  std::size_t take() {
    if (next_ == in_.size()) in_.fail("the line ends before all of the element's properties");
    return next_++;
  }

  TextScanner in_;
  std::size_t next_ = 0;
};

// Binary values, checked for truncation value by value.
class BinaryValues {
 public:
  BinaryValues(std::string_view data, std::size_t offset, bool big_endian, const std::string& file)
      : bytes_(data, offset, big_endian), file_(file) {}

  void begin(const PlyElement& element, std::uint64_t i) {
    element_ = &element;
    index_ = i;
  }
  double real(PlyType type) {
    require(size_of(type));
    switch (type) {
      case PlyType::kFloat32:
        return static_cast<double>(bytes_.read<float>());
      case PlyType::kFloat64:
        return bytes_.read<double>();
      default:
        return static_cast<double>(read_integer(type));
    }
  }
  std::int64_t integer(PlyType type) {
    require(size_of(type));
    return read_integer(type);
  }
  void end(const PlyElement&, std::uint64_t) {}
  void finish() {
    if (bytes_.remaining() > 0) {
      throw InputError(file_, std::to_string(bytes_.remaining()) +
                                  " bytes of unexpected data after the last element");
    }
  }
  [[nodiscard]] std::size_t line() const { return 0; }
  [[noreturn]] void fail(const std::string& message) const {
    throw InputError(file_,
                     message + " (binary data at byte " + std::to_string(bytes_.offset()) + ")");
  }

 private:
  void require(std::size_t size) {
    if (!bytes_.has(size)) {
      throw InputError(file_, "the file ends inside " + element_->name + " " +
                                  std::to_string(index_) + " (the header declares " +
                                  std::to_string(element_->count) + " " + element_->name +
                                  " elements)");
    }
  }
  std::int64_t read_integer(PlyType type) {
    switch (type) {
      case PlyType::kInt8:
        return bytes_.read<std::int8_t>();
      case PlyType::kUInt8:
        return bytes_.read<std::uint8_t>();
      case PlyType::kInt16:
        return bytes_.read<std::int16_t>();
      case PlyType::kUInt16:
        return bytes_.read<std::uint16_t>();
      case PlyType::kInt32:
        return bytes_.read<std::int32_t>();
      case PlyType::kUInt32:
        return bytes_.read<std::uint32_t>();
      default:
        return 0;  // float types never reach here: the header check rejects them
    }
  }

  ByteReader bytes_;
  const std::string& file_;
  const PlyElement* element_ = nullptr;
  std::uint64_t index_ = 0;
};

// Where the vertex coordinates and the face corners are among the properties.
struct SurfaceLayout {
  const PlyElement* vertex = nullptr;
  std::size_t xyz[3] = {};
  const PlyElement* face = nullptr;
  std::size_t corners = 0;
};

SurfaceLayout find_surface(const PlyHeader& header, const std::string& file) {
  SurfaceLayout layout;
  for (const PlyElement& element : header.elements) {
    if (element.name == "vertex") layout.vertex = &element;
    if (element.name == "face") layout.face = &element;
  }
  if (!layout.vertex) throw InputError(file, "the header declares no 'vertex' element");
  if (!layout.face) throw InputError(file, "the header declares no 'face' element: not a surface");
  const char* axes[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    bool found = false;
    for (std::size_t p = 0; p < layout.vertex->properties.size(); ++p) {
      const PlyProperty& property = layout.vertex->properties[p];
      if (property.name != axes[k]) continue;
      if (property.list_count) {
        throw InputError(file, "vertex property '" + property.name + "' is a list");
      }
      layout.xyz[k] = p;
      found = true;
    }
    if (!found) {
      throw InputError(file, std::string("the vertex element has no '") + axes[k] + "' property");
    }
  }
  bool found = false;
  for (std::size_t p = 0; p < layout.face->properties.size(); ++p) {
    const PlyProperty& property = layout.face->properties[p];
    if (property.name != "vertex_indices" && property.name != "vertex_index") continue;
    if (!property.list_count || !is_integer(property.type)) {
      throw InputError(file, "face property '" + property.name + "' must be a list of integers");
    }
    layout.corners = p;
    found = true;
  }
  if (!found) throw InputError(file, "the face element has no 'vertex_indices' list");
  return layout;
}

template <class Values>
void skip_value(Values& values, PlyType type) {
  if (is_integer(type)) {
    (void)values.integer(type);
  } else {
    (void)values.real(type);
  }
}

template <class Values>
void skip_property(Values& values, const PlyProperty& property) {
  if (!property.list_count) {
    skip_value(values, property.type);
    return;
  }
  const std::int64_t n = values.integer(*property.list_count);
  if (n < 0) values.fail("list '" + property.name + "' has negative length " + std::to_string(n));
  for (std::int64_t k = 0; k < n; ++k) {
    skip_value(values, property.type);
  }
}

template <class Values>
void read_body(Values& values, const PlyHeader& header, const SurfaceLayout& layout,
               SurfaceBuilder& builder) {
  std::vector<std::int64_t> corners;
  for (const PlyElement& element : header.elements) {
    // An element without properties takes no bytes (and blank lines, which are skipped): do not
    // spin through a corrupt count of them.
    if (element.properties.empty()) continue;
    for (std::uint64_t i = 0; i < element.count; ++i) {
      values.begin(element, i);
      glm::dvec3 position(0.0);
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const PlyProperty& property = element.properties[p];
        if (&element == layout.vertex && !property.list_count) {
          const double value = values.real(property.type);
          for (int k = 0; k < 3; ++k) {
            if (p == layout.xyz[k]) position[k] = value;
          }
        } else if (&element == layout.face && p == layout.corners) {
          const std::int64_t n = values.integer(*property.list_count);
          if (n < 0) {
            values.fail("face " + std::to_string(i) + " has negative length " + std::to_string(n));
          }
          corners.clear();
          for (std::int64_t k = 0; k < n; ++k) {
            corners.push_back(values.integer(property.type));
          }
        } else {
          skip_property(values, property);
        }
      }
      values.end(element, i);
      if (&element == layout.vertex) builder.add_vertex(position, values.line());
      if (&element == layout.face) builder.add_polygon(corners, i, values.line());
    }
  }
  values.finish();
}

}  // namespace

ParsedSurface read_ply(std::string_view data, const std::string& file) {
  const std::string& name = file;
  const PlyHeader header = parse_ply_header(data, name);
  const SurfaceLayout layout = find_surface(header, name);
  // Faces are read after vertices so that add_polygon can check their indices.
  for (const PlyElement& element : header.elements) {
    if (&element == layout.face) {
      throw InputError(name, "the 'face' element comes before the 'vertex' element");
    }
    if (&element == layout.vertex) break;
  }

  check_ply_counts(header, data.size(), name);
  SurfaceBuilder builder(name, 0);
  builder.reserve(layout.vertex->count, layout.face->count, data.size());
  if (header.encoding == PlyEncoding::kAscii) {
    AsciiValues values(data.substr(header.body_offset), name, header.body_first_line);
    read_body(values, header, layout, builder);
  } else {
    BinaryValues values(data, header.body_offset, header.encoding == PlyEncoding::kBinaryBigEndian,
                        name);
    read_body(values, header, layout, builder);
  }
  return std::move(builder).finish();
}

}  // namespace deformcd::io
