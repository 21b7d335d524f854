// Reading TetGen's .node/.ele/.face files, as TetGen writes them and reads them back.
// Formats: https://wias-berlin.de/software/tetgen/fformats.html
//   .node  <#points> <dimension=3> <#attributes> <boundary markers 0/1>
//          <index> <x> <y> <z> [attributes] [boundary marker]
//   .ele   <#tetrahedra> <nodes per tetrahedron=4> <#region attributes>
//          <index> <n1> <n2> <n3> <n4> [region attributes]
//   .face  <#faces> <boundary markers 0/1>
//          <index> <n1> <n2> <n3> [boundary marker]
// Header fields after the count are optional, with TetGen's defaults (3, 0, 0 / 4, 0 / 0).
// Attributes and markers are checked to be numbers and otherwise ignored. Indices are 0- or
// 1-based, as the first node's index says; every file's record indices must then run
// consecutively from that base, which catches lost or duplicated lines.

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "deformcd/error.h"
#include "deformcd/io.h"
#include "deformcd/mesh_validation.h"
#include "io/tetgen_files.h"
#include "io/text_scanner.h"

namespace deformcd {

namespace {

using io::TextScanner;

std::string count_of(std::size_t n, const char* singular, const char* plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

// "expected 6 numbers (index, 3 coordinates, 1 attribute and a boundary marker), found 4"
std::string expected_fields(std::size_t total, bool all_integers, std::vector<std::string> parts,
                            std::size_t found) {
  std::string list;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (i > 0) list += i + 1 == parts.size() ? " and " : ", ";
    list += parts[i];
  }
  return "expected " + std::to_string(total) + (all_integers ? " integers (" : " numbers (") +
         list + "), found " + std::to_string(found);
}

struct NodeFile {
  std::vector<glm::dvec3> nodes;
  std::vector<std::size_t> lines;
  unsigned base = 0;
};

NodeFile read_node_file(const io::TetGenText& file) {
  TextScanner in(file.text, file.name);
  if (!in.next_record()) {
    in.fail_at_end(
        "no header: expected '<#points> <dimension> <#attributes> <boundary markers 0/1>'");
  }
  if (in.size() > 4) {
    in.fail(
        "expected at most 4 integers in the header (#points, dimension, #attributes, "
        "boundary markers 0/1), found " +
        std::to_string(in.size()));
  }
  const auto count = in.integer<std::uint32_t>(0);
  const auto dimension = in.size() > 1 ? in.integer<std::int64_t>(1) : 3;
  if (dimension != 3) {
    in.fail("dimension is " + std::to_string(dimension) +
            "; only 3-dimensional meshes are supported");
  }
  const auto attributes = in.size() > 2 ? in.integer<std::uint32_t>(2) : 0u;
  const auto markers = in.size() > 3 ? in.integer<std::int64_t>(3) : 0;
  if (markers != 0 && markers != 1) {
    in.fail("the boundary marker flag must be 0 or 1, found " + std::to_string(markers));
  }

  std::vector<std::string> parts = {"index", "3 coordinates"};
  if (attributes > 0) parts.push_back(count_of(attributes, "attribute", "attributes"));
  if (markers) parts.emplace_back("a boundary marker");
  const std::size_t fields = 4 + std::size_t{attributes} + static_cast<std::size_t>(markers);

  in.check_line_count(count, "node", "nodes");
  NodeFile result;
  // A node line takes at least 8 bytes ("i x y z\n"): a count within the lines but past that
  // (a wrong count, or a file whose lines are short) reserves no more than the file can hold.
  result.nodes.reserve(std::min<std::size_t>(count, file.text.size() / 8));
  result.lines.reserve(result.nodes.capacity());
  for (std::uint32_t i = 0; i < count; ++i) {
    if (!in.next_record()) {
      in.fail_at_end("expected " + std::to_string(count) + " nodes, file ends after " +
                     std::to_string(i));
    }
    if (in.size() != fields) in.fail(expected_fields(fields, false, parts, in.size()));
    const auto index = in.integer<std::int64_t>(0);
    if (i == 0) {
      if (index != 0 && index != 1) {
        in.fail("the first node's index must be 0 or 1, found " + std::to_string(index));
      }
      result.base = static_cast<unsigned>(index);
    } else if (index != std::int64_t{i} + result.base) {
      in.fail("expected node index " + std::to_string(std::int64_t{i} + result.base) +
              " (indices must be consecutive), found " + std::to_string(index));
    }
    result.nodes.emplace_back(in.real(1), in.real(2), in.real(3));
    for (std::size_t k = 4; k < 4 + attributes; ++k) {
      (void)in.real(k);
    }
    if (markers) (void)in.integer<std::int64_t>(fields - 1);
    result.lines.push_back(in.line());
  }
  if (in.next_record()) {
    in.fail("unexpected content after the " + count_of(count, "declared node", "declared nodes"));
  }
  return result;
}

// What follows the node indices on an element record, and how to name the element.
struct ElementLayout {
  const char* singular;  // "tetrahedron"
  const char* plural;    // "tetrahedra"
  std::uint32_t real_attributes = 0;
  bool marker = false;
};

template <std::size_t N>
struct ElementFile {
  std::vector<std::array<std::uint32_t, N>> elements;
  std::vector<std::size_t> lines;
};

// Reads `count` records of `index n1..nN [attributes] [marker]` after the header.
template <std::size_t N>
ElementFile<N> read_element_records(TextScanner& in, std::uint32_t count,
                                    const ElementLayout& layout, const NodeFile& nodes) {
  std::vector<std::string> parts = {"index", std::to_string(N) + " nodes"};
  if (layout.real_attributes > 0) {
    parts.push_back(count_of(layout.real_attributes, "region attribute", "region attributes"));
  }
  if (layout.marker) parts.emplace_back("a boundary marker");
  const std::size_t fields = 1 + N + std::size_t{layout.real_attributes} + (layout.marker ? 1 : 0);
  const bool all_integers = layout.real_attributes == 0;
  const std::int64_t base = nodes.base;
  const std::int64_t node_count = static_cast<std::int64_t>(nodes.nodes.size());

  in.check_line_count(count, layout.singular, layout.plural);
  ElementFile<N> result;
  // Likewise: an element line takes at least 2 (N + 1) bytes.
  result.elements.reserve(std::min<std::size_t>(count, in.text_size() / (2 * (N + 1))));
  result.lines.reserve(result.elements.capacity());
  for (std::uint32_t i = 0; i < count; ++i) {
    if (!in.next_record()) {
      in.fail_at_end("expected " + std::to_string(count) + " " + layout.plural +
                     ", file ends after " + std::to_string(i));
    }
    if (in.size() != fields) in.fail(expected_fields(fields, all_integers, parts, in.size()));
    const auto index = in.integer<std::int64_t>(0);
    auto name = [&] { return std::string(layout.singular) + " " + std::to_string(index); };
    if (index != std::int64_t{i} + base) {
      in.fail("expected " + std::string(layout.singular) + " index " +
              std::to_string(std::int64_t{i} + base) + " (indices must be consecutive from " +
              std::to_string(base) + ", as the nodes'), found " + std::to_string(index));
    }
    std::array<std::uint32_t, N> element{};
    for (std::size_t k = 0; k < N; ++k) {
      const auto node = in.integer<std::int64_t>(1 + k);
      if (node < base || node - base >= node_count) {
        in.fail(name() + " refers to node " + std::to_string(node) + ", out of range (valid: " +
                std::to_string(base) + ".." + std::to_string(node_count - 1 + base) + ")");
      }
      element[k] = static_cast<std::uint32_t>(node - base);
      for (std::size_t j = 0; j < k; ++j) {
        if (element[j] == element[k]) in.fail(name() + " repeats node " + std::to_string(node));
      }
    }
    for (std::size_t k = 1 + N; k < 1 + N + layout.real_attributes; ++k) {
      (void)in.real(k);
    }
    if (layout.marker) (void)in.integer<std::int64_t>(fields - 1);
    result.elements.push_back(element);
    result.lines.push_back(in.line());
  }
  if (in.next_record()) {
    in.fail("unexpected content after the " + std::to_string(count) + " declared " +
            (count == 1 ? layout.singular : layout.plural));
  }
  return result;
}

ElementFile<4> read_ele_file(const io::TetGenText& file, const NodeFile& nodes) {
  TextScanner in(file.text, file.name);
  if (!in.next_record()) {
    in.fail_at_end(
        "no header: expected '<#tetrahedra> <nodes per tetrahedron> <#region attributes>'");
  }
  if (in.size() > 3) {
    in.fail(
        "expected at most 3 integers in the header (#tetrahedra, nodes per tetrahedron, "
        "#region attributes), found " +
        std::to_string(in.size()));
  }
  const auto count = in.integer<std::uint32_t>(0);
  const auto corners = in.size() > 1 ? in.integer<std::int64_t>(1) : 4;
  if (corners == 10) {
    // Taking the 4 corners would leave the 6 edge-midpoint nodes unreferenced: free particles.
    in.fail("second-order tetrahedra (10 nodes each) are not supported; mesh without -o2");
  }
  if (corners != 4) {
    in.fail("tetrahedra must have 4 nodes, the header says " + std::to_string(corners));
  }
  ElementLayout layout{"tetrahedron", "tetrahedra"};
  layout.real_attributes = in.size() > 2 ? in.integer<std::uint32_t>(2) : 0u;
  return read_element_records<4>(in, count, layout, nodes);
}

// `tetrahedra`, read from `ele`, bound the count: each face is a face of one of them (TetGen
// writes the boundary faces, or with -f every face), so there are at most 4 per tetrahedron.
ElementFile<3> read_face_file(const io::TetGenText& file, const NodeFile& nodes,
                              std::size_t tetrahedra, const std::string& ele) {
  TextScanner in(file.text, file.name);
  if (!in.next_record()) in.fail_at_end("no header: expected '<#faces> <boundary markers 0/1>'");
  if (in.size() > 2) {
    in.fail("expected at most 2 integers in the header (#faces, boundary markers 0/1), found " +
            std::to_string(in.size()));
  }
  const auto count = in.integer<std::uint32_t>(0);
  const auto markers = in.size() > 1 ? in.integer<std::int64_t>(1) : 0;
  if (markers != 0 && markers != 1) {
    in.fail("the boundary marker flag must be 0 or 1, found " + std::to_string(markers));
  }
  if (count > 4 * std::uint64_t{tetrahedra}) {
    in.fail("declares " + count_of(count, "face", "faces") + ", but the " +
            count_of(tetrahedra, "tetrahedron", "tetrahedra") + " of " + ele + " have only " +
            std::to_string(4 * std::uint64_t{tetrahedra}) +
            " faces: the .face does not belong to this .ele");
  }
  ElementLayout layout{"face", "faces"};
  layout.marker = markers == 1;
  return read_element_records<3>(in, count, layout, nodes);
}

}  // namespace

namespace io {

TetMesh parse_tetgen(const TetGenText& node, const TetGenText& ele,
                     const std::optional<TetGenText>& face) {
  NodeFile nodes = read_node_file(node);
  ElementFile<4> tetrahedra = read_ele_file(ele, nodes);

  TetMesh mesh;
  if (face) {
    mesh.faces =
        std::move(read_face_file(*face, nodes, tetrahedra.elements.size(), ele.name).elements);
  }
  mesh.nodes = std::move(nodes.nodes);
  mesh.tetrahedra = std::move(tetrahedra.elements);

  MeshSource source;
  source.vertex_file = node.name;
  source.vertex_lines = std::move(nodes.lines);
  source.element_file = ele.name;
  source.element_lines = std::move(tetrahedra.lines);
  source.index_base = nodes.base;
  validate_tet_mesh(mesh, source);
  return mesh;
}

}  // namespace io

TetMesh read_tetgen(const std::filesystem::path& prefix) {
  const io::TetGenFiles files = io::tetgen_files(prefix);
  const std::string node = io::read_whole_file(files.node);
  const std::string ele = io::read_whole_file(files.ele);
  std::optional<std::string> face;
  std::error_code ec;
  if (std::filesystem::exists(files.face, ec)) face = io::read_whole_file(files.face);
  std::optional<io::TetGenText> face_text;
  if (face) face_text = io::TetGenText{files.face.string(), *face};
  return io::parse_tetgen({files.node.string(), node}, {files.ele.string(), ele}, face_text);
}

}  // namespace deformcd
