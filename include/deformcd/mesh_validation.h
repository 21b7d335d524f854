#pragma once
/// \file mesh_validation.h
/// The contracts of SurfaceMesh and TetMesh, checked with errors that say where they break.

#include <cstddef>
#include <string>
#include <vector>

#include "deformcd/mesh.h"

namespace deformcd {

/// Where a mesh came from, so that errors can name the file and line of the bad element.
/// Line vectors may be empty (then errors name the element index only).
struct MeshSource {
  std::string vertex_file;                 ///< file holding the vertices / nodes
  std::vector<std::size_t> vertex_lines;   ///< 1-based line of each vertex, if known
  std::string element_file;                ///< file holding the triangles / tetrahedra
  std::vector<std::size_t> element_lines;  ///< 1-based line of each element, if known
  unsigned index_base = 0;                 ///< first index in the file (0 or 1), for messages
};

/// Relative size below which an element counts as degenerate: a triangle whose area is below
/// kDegenerateRelTol x (longest edge)^2, a tetrahedron whose volume is below
/// kDegenerateRelTol x (longest edge)^3. Scale-independent.
inline constexpr double kDegenerateRelTol = 1e-12;

/// Throws InputError unless: every coordinate is finite, every index is in range, no triangle
/// repeats a vertex or has (near-)zero area.
void validate_surface_mesh(const SurfaceMesh& mesh, const MeshSource& source);

/// Throws InputError unless: coordinates finite, indices in range, no tetrahedron repeats a node
/// or has (near-)zero volume, and all tetrahedra have the same orientation. A mesh whose
/// tetrahedra are all negatively oriented (the other common convention) is reoriented in place
/// to the positive orientation TetMesh promises; a tetrahedron whose orientation differs from
/// the majority is reported as inverted. Faces (if any) are checked for range too.
void validate_tet_mesh(TetMesh& mesh, const MeshSource& source);

}  // namespace deformcd
