#pragma once
/// \file mesh.h
/// Meshes as read from files, in double precision, before they become bodies.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace deformcd {

/// Three vertex indices.
using Triangle = std::array<std::uint32_t, 3>;
/// Four node indices.
using Tetrahedron = std::array<std::uint32_t, 4>;

/// A triangulated surface (OFF, OBJ, STL, PLY). Vertices keep the file's order.
struct SurfaceMesh {
  std::vector<glm::dvec3> vertices;  ///< in the file's order
  std::vector<Triangle> triangles;   ///< indices into vertices
};

/// A tetrahedral mesh (TetGen .node/.ele/.face). Indices are 0-based whatever the file used.
/// Tetrahedra are positively oriented: dot(b-a, cross(c-a, d-a)) > 0 for (a, b, c, d).
struct TetMesh {
  std::vector<glm::dvec3> nodes;        ///< node positions
  std::vector<Tetrahedron> tetrahedra;  ///< indices into nodes, positively oriented
  /// Faces listed in a .face file, if one was read (boundary faces, as TetGen writes them).
  /// Bodies do not use these: their surface is recomputed from the tetrahedra.
  std::vector<Triangle> faces;
};

}  // namespace deformcd
