#pragma once
/// \file collision_mesh.h
/// The meshes a Detector tests (detector.h), and which of them are tested against which: plain
/// data, also what the collision code under the Detector lays out.

#include <cstdint>
#include <string>
#include <vector>

#include "deformcd/mesh.h"

namespace deformcd {

/// One mesh as the detector sees it: triangles indexing its vertices [0, vertex_count).
struct CollisionMesh {
  std::uint32_t vertex_count = 0;  ///< the mesh's vertices are 0 .. vertex_count - 1
  /// Counter-clockwise or not, in any order: contacts name them by their index here.
  std::vector<Triangle> triangles = {};
  /// Also test the mesh's triangles against each other (triangles sharing an edge are never a
  /// contact; triangles sharing a vertex are when they also meet elsewhere).
  bool self_collision = false;
  /// For messages ("mesh 1 ('cloth')"); may be empty.
  std::string name = {};
};

/// Two meshes whose triangles are tested against each other (a != b; a == b means the mesh
/// with itself, as CollisionMesh::self_collision).
struct MeshPair {
  std::uint32_t a = 0;  ///< a mesh index
  std::uint32_t b = 0;  ///< the other mesh index (== a: the mesh with itself)
};

}  // namespace deformcd
