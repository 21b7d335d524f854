#include "deformcd/mesh_validation.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/geometry.h"
#include "deformcd/error.h"

namespace deformcd {

namespace {

std::size_t line_of(const std::vector<std::size_t>& lines, std::size_t i) {
  return i < lines.size() ? lines[i] : 0;
}

[[noreturn]] void fail_vertex(const MeshSource& src, std::size_t i, const std::string& what) {
  std::ostringstream msg;
  msg << "vertex " << i + src.index_base << ' ' << what;
  throw InputError(src.vertex_file, line_of(src.vertex_lines, i), msg.str());
}

template <class Element>
[[noreturn]] void fail_element(const MeshSource& src, const char* kind, std::size_t i,
                               const Element& e, const std::string& what) {
  std::ostringstream msg;
  msg << kind << ' ' << i + src.index_base << " (";
  for (std::size_t k = 0; k < e.size(); ++k)
    msg << (k ? " " : "") << e[k] + src.index_base;
  msg << ") " << what;
  throw InputError(src.element_file, line_of(src.element_lines, i), msg.str());
}

void check_vertices(const std::vector<glm::dvec3>& vertices, const MeshSource& src) {
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (!geom::is_finite(vertices[i])) fail_vertex(src, i, "has a NaN or infinite coordinate");
  }
}

template <class Element>
void check_indices(const Element& e, std::size_t i, std::size_t vertex_count, const char* kind,
                   const MeshSource& src) {
  for (std::size_t k = 0; k < e.size(); ++k) {
    if (e[k] >= vertex_count) {
      std::ostringstream msg;
      msg << "refers to vertex " << e[k] + src.index_base
          << ", out of range (valid: " << src.index_base << ".."
          << vertex_count - 1 + src.index_base << ")";
      fail_element(src, kind, i, e, msg.str());
    }
    for (std::size_t j = 0; j < k; ++j) {
      if (e[j] == e[k]) fail_element(src, kind, i, e, "repeats a vertex");
    }
  }
}

}  // namespace

void validate_surface_mesh(const SurfaceMesh& mesh, const MeshSource& src) {
  if (mesh.vertices.empty()) throw InputError(src.vertex_file, "has no vertices");
  if (mesh.triangles.empty()) throw InputError(src.element_file, "has no triangles");
  check_vertices(mesh.vertices, src);
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const Triangle& t = mesh.triangles[i];
    check_indices(t, i, mesh.vertices.size(), "triangle", src);
    const glm::dvec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const double area2 = geom::double_area(a, b, c);
    if (!(area2 > kDegenerateRelTol * geom::longest_edge2(a, b, c))) {
      fail_element(src, "triangle", i, t, "is degenerate (zero area)");
    }
  }
}

void validate_tet_mesh(TetMesh& mesh, const MeshSource& src) {
  if (mesh.nodes.empty()) throw InputError(src.vertex_file, "has no nodes");
  if (mesh.tetrahedra.empty()) throw InputError(src.element_file, "has no tetrahedra");
  check_vertices(mesh.nodes, src);

  std::vector<signed char> sign(mesh.tetrahedra.size());
  std::size_t positive = 0;
  for (std::size_t i = 0; i < mesh.tetrahedra.size(); ++i) {
    const Tetrahedron& t = mesh.tetrahedra[i];
    check_indices(t, i, mesh.nodes.size(), "tetrahedron", src);
    const glm::dvec3 &a = mesh.nodes[t[0]], &b = mesh.nodes[t[1]], &c = mesh.nodes[t[2]],
                     &d = mesh.nodes[t[3]];
    const double v6 = geom::signed_volume6(a, b, c, d);
    const double edge2 = std::max({geom::longest_edge2(a, b, c), glm::dot(d - a, d - a),
                                   glm::dot(d - b, d - b), glm::dot(d - c, d - c)});
    if (!(std::abs(v6) > kDegenerateRelTol * edge2 * std::sqrt(edge2))) {
      fail_element(src, "tetrahedron", i, t, "is degenerate (zero volume)");
    }
    sign[i] = v6 > 0 ? 1 : -1;
    positive += v6 > 0 ? 1 : 0;
  }
  // The majority orientation is the file's convention; a tetrahedron against it is inverted.
  const bool file_positive = 2 * positive >= mesh.tetrahedra.size();
  for (std::size_t i = 0; i < mesh.tetrahedra.size(); ++i) {
    if ((sign[i] > 0) != file_positive) {
      fail_element(src, "tetrahedron", i, mesh.tetrahedra[i],
                   "is inverted (its orientation is opposite to the other tetrahedra's)");
    }
  }
  if (!file_positive) {
    for (Tetrahedron& t : mesh.tetrahedra)
      std::swap(t[2], t[3]);
  }

  MeshSource face_src = src;
  face_src.element_lines.clear();
  for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
    check_indices(mesh.faces[i], i, mesh.nodes.size(), "face", face_src);
  }
}

}  // namespace deformcd
