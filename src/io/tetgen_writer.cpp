// Writing TetGen's .node/.ele/.face files, 0-based, in the layout TetGen itself writes:
//   .node  "<#nodes> 3 0 0"       then "<index> <x> <y> <z>"
//   .ele   "<#tetrahedra> 4 0"    then "<index> <n1> <n2> <n3> <n4>"
//   .face  "<#faces> 1"           then "<index> <n1> <n2> <n3> 1"
// The .face file carries boundary markers, all 1: TetGen marks the faces on the mesh's hull with
// 1 when the input has no facet markers, and mesh.faces are such boundary faces. The .face file
// is written even when mesh.faces is empty (a header "0 1"), so that a stale .face from an
// earlier mesh under the same prefix can never be read with the new nodes.
// Coordinates are written in the shortest form that reads back to the same double.

#include <cmath>
#include <string>
#include <vector>

#include "deformcd/error.h"
#include "deformcd/io.h"
#include "io/atomic_file.h"
#include "io/tetgen_files.h"
#include "io/text_writer.h"

namespace deformcd {

namespace {

using io::append_integer;
using io::append_real;

// The mesh must read back: finite coordinates and indices in range.
template <class Element>
void check_indices(const std::vector<Element>& elements, const char* kind, std::size_t nodes) {
  for (std::size_t i = 0; i < elements.size(); ++i) {
    for (const std::uint32_t node : elements[i]) {
      if (node >= nodes) {
        throw Error("write_tetgen: " + std::string(kind) + " " + std::to_string(i) +
                    " refers to node " + std::to_string(node) + ", but the mesh has " +
                    std::to_string(nodes) + " nodes");
      }
    }
  }
}

void check_writable(const TetMesh& mesh) {
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    const glm::dvec3& p = mesh.nodes[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      throw Error("write_tetgen: node " + std::to_string(i) + " has a NaN or infinite coordinate");
    }
  }
  check_indices(mesh.tetrahedra, "tetrahedron", mesh.nodes.size());
  check_indices(mesh.faces, "face", mesh.nodes.size());
}

std::string comment_line(const std::filesystem::path& file) {
  return "# " + file.filename().string() + ", written by deformcd (0-based indices)\n";
}

std::string node_text(const TetMesh& mesh, const std::filesystem::path& file) {
  std::string out = comment_line(file);
  out.reserve(mesh.nodes.size() * 64);
  append_integer(out, mesh.nodes.size());
  out += " 3 0 0\n";
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    append_integer(out, i);
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      append_real(out, mesh.nodes[i][k]);
    }
    out += '\n';
  }
  return out;
}

template <class Element>
std::string element_text(const std::vector<Element>& elements, const std::string& header,
                         const char* suffix, const std::filesystem::path& file) {
  std::string out = comment_line(file);
  out.reserve(elements.size() * 8 * (elements.empty() ? 0 : elements[0].size() + 1));
  append_integer(out, elements.size());
  out += header;
  for (std::size_t i = 0; i < elements.size(); ++i) {
    append_integer(out, i);
    for (const std::uint32_t node : elements[i]) {
      out += ' ';
      append_integer(out, node);
    }
    out += suffix;
  }
  return out;
}

}  // namespace

namespace io {

TetGenFileTexts tetgen_texts(const TetMesh& mesh, const TetGenFiles& files) {
  check_writable(mesh);
  return {node_text(mesh, files.node), element_text(mesh.tetrahedra, " 4 0\n", "\n", files.ele),
          element_text(mesh.faces, " 1\n", " 1\n", files.face)};
}

}  // namespace io

void write_tetgen(const TetMesh& mesh, const std::filesystem::path& prefix) {
  const io::TetGenFiles files = io::tetgen_files(prefix);
  io::TetGenFileTexts texts = io::tetgen_texts(mesh, files);
  const io::FileContents contents[] = {
      {files.node, std::move(texts.node)},
      {files.ele, std::move(texts.ele)},
      {files.face, std::move(texts.face)},
  };
  io::write_files_atomically(contents);
}

}  // namespace deformcd
