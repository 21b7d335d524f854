#include "io/ply_header.h"

#include <array>
#include <string>
#include <utility>

#include "deformcd/error.h"
#include "io/text_scanner.h"

namespace deformcd::io {

namespace {

// Both the original names and the sized ones that later writers use.
constexpr std::array<std::pair<std::string_view, PlyType>, 16> kTypeNames = {{
    {"char", PlyType::kInt8},
    {"int8", PlyType::kInt8},
    {"uchar", PlyType::kUInt8},
    {"uint8", PlyType::kUInt8},
    {"short", PlyType::kInt16},
    {"int16", PlyType::kInt16},
    {"ushort", PlyType::kUInt16},
    {"uint16", PlyType::kUInt16},
    {"int", PlyType::kInt32},
    {"int32", PlyType::kInt32},
    {"uint", PlyType::kUInt32},
    {"uint32", PlyType::kUInt32},
    {"float", PlyType::kFloat32},
    {"float32", PlyType::kFloat32},
    {"double", PlyType::kFloat64},
    {"float64", PlyType::kFloat64},
}};

PlyType type_named(const TextScanner& in, std::size_t i) {
  for (const auto& [name, type] : kTypeNames) {
    if (in.token(i) == name) return type;
  }
  in.fail("unknown property type '" + std::string(in.token(i)) + "'");
}

void parse_format(const TextScanner& in, PlyHeader& header) {
  if (in.size() != 3) {
    in.fail("expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
  }
  const std::string_view name = in.token(1);
  if (name == "ascii") {
    header.encoding = PlyEncoding::kAscii;
  } else if (name == "binary_little_endian") {
    header.encoding = PlyEncoding::kBinaryLittleEndian;
  } else if (name == "binary_big_endian") {
    header.encoding = PlyEncoding::kBinaryBigEndian;
  } else {
    in.fail("unknown PLY format '" + std::string(name) + "'");
  }
  if (in.token(2) != "1.0") in.fail("unsupported PLY version '" + std::string(in.token(2)) + "'");
}

PlyProperty parse_property(const TextScanner& in) {
  PlyProperty property;
  if (in.size() >= 2 && in.token(1) == "list") {
    if (in.size() != 5) in.fail("expected 'property list <count type> <item type> <name>'");
    property.list_count = type_named(in, 2);
    if (!is_integer(*property.list_count)) in.fail("a list's count type must be an integer type");
    property.type = type_named(in, 3);
    property.name = in.token(4);
  } else {
    if (in.size() != 3) in.fail("expected 'property <type> <name>'");
    property.type = type_named(in, 1);
    property.name = in.token(2);
  }
  return property;
}

}  // namespace

std::size_t size_of(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
    case PlyType::kUInt8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUInt16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUInt32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 0;
}

bool is_integer(PlyType type) {
  return type != PlyType::kFloat32 && type != PlyType::kFloat64;
}

PlyHeader parse_ply_header(std::string_view data, const std::string& file) {
  // The header is text even in binary files; stop reading lines at "end_header".
  TextScanner in(data, file, /*hash_comments=*/false);
  if (!in.next_record() || in.size() != 1 || in.token(0) != "ply") {
    throw InputError(file, 1, "not a PLY file: the first line must be 'ply'");
  }
  PlyHeader header;
  bool has_format = false;
  for (;;) {
    if (!in.next_record()) in.fail_at_end("the header has no 'end_header' line");
    const std::string_view keyword = in.token(0);
    if (keyword == "end_header") {
      if (in.size() != 1) in.fail("unexpected text after 'end_header'");
      break;
    }
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      parse_format(in, header);
      has_format = true;
    } else if (keyword == "element") {
      if (in.size() != 3) in.fail("expected 'element <name> <count>'");
      header.elements.push_back(
          {std::string(in.token(1)), in.integer<std::uint64_t>(2), {}, in.line()});
    } else if (keyword == "property") {
      if (header.elements.empty()) in.fail("'property' before any 'element'");
      header.elements.back().properties.push_back(parse_property(in));
    } else {
      in.fail("unknown header keyword '" + std::string(keyword) + "'");
    }
  }
  if (!has_format) in.fail("the header has no 'format' line");
  header.body_offset = in.offset_after_record();
  header.body_first_line = in.line() + 1;
  return header;
}

void check_ply_counts(const PlyHeader& header, std::size_t file_size, const std::string& file) {
  const bool ascii = header.encoding == PlyEncoding::kAscii;
  const std::uint64_t body = file_size - header.body_offset;
  // ASCII: one element per non-blank line, at least a character and a newline (the last line
  // may lack it, hence the + 1).
  const std::uint64_t room = ascii ? body + 1 : body;
  std::uint64_t used = 0;
  for (const PlyElement& element : header.elements) {
    std::uint64_t size = 0;  // the fewest bytes one element takes
    for (const PlyProperty& property : element.properties) {
      size += size_of(property.list_count ? *property.list_count : property.type);
    }
    if (ascii && size > 0) size = 2;
    if (size == 0) continue;  // no properties: takes no bytes, and the reader skips it
    if (element.count > (room - used) / size) {
      const std::string each =
          ascii ? "one per line"
                : "at least " + std::to_string(size) + (size == 1 ? " byte each" : " bytes each");
      throw InputError(
          file, element.line,
          "declares " + std::to_string(element.count) + " '" + element.name + "' elements (" +
              each + "), but the body after the header has " + std::to_string(body) + " bytes" +
              (used > 0 ? ", " + std::to_string(used) + " of them for the elements before" : "") +
              ": a wrong count or a truncated file");
    }
    used += element.count * size;
  }
}

}  // namespace deformcd::io
