#pragma once
// The narrow phase of one pair of surface faces, given by their nodes, for faces of two bodies
// and for two faces of one body (self-collision). Faces that share nodes touch there by
// construction, so the plain triangle test would report every neighbour in the surface:
//  - faces sharing an edge (two nodes) are never a contact: they are neighbours in the surface;
//  - faces sharing one node are a contact only when they meet somewhere else too. Their
//    intersection is convex and holds the shared node v; when it holds another point x, the
//    ray from v through x leaves each triangle through its edge opposite v, and the nearer of
//    the two exits lies in the other triangle. So: they meet beyond v exactly when the edge
//    opposite v of one triangle meets the other triangle (which also covers coplanar overlaps);
//  - faces sharing no node take the triangle test.
// shaders/collision/face_pair_intersection.glsl mirrors this file; change both together.

#include <cstdint>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/collision/tri_tri_intersection.h"
#include "core/collision/vertex_positions.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::collision {

/// The nodes two faces share: how many, and at which corner (0, 1, 2 for a, b, c) of each face
/// the first shared node sits (meaningful when count >= 1).
struct SharedNodes {
  int count = 0;
  int corner_a = 0;
  int corner_b = 0;
};

/// Faces of different meshes (Face::body) share no node: their indices are local to their mesh.
[[nodiscard]] SharedNodes shared_nodes(const gpu::Face& a, const gpu::Face& b);

/// Whether the closed segment [s0, s1] and triangle t share a point, with the tolerances of
/// tri_tri_intersect (relative to the longer of the segment and t's longest edge; touching
/// counts). A degenerate t (see kTriTriDegenerateTolerance) meets nothing.
[[nodiscard]] bool segment_triangle_meet(const glm::vec3& s0, const glm::vec3& s1,
                                         const glm::vec3 t[3]);

/// Triangles p and q that share their first vertex (p[0] == q[0], the same node): they
/// intersect when they meet anywhere besides it (see above). The result is then that of
/// tri_tri_intersect(p, q), whose segment starts or ends at the shared vertex. Symmetric.
[[nodiscard]] TriTriResult tri_tri_intersect_sharing_vertex(const glm::vec3 p[3],
                                                            const glm::vec3 q[3]);

/// The narrow phase of faces fa and fb with their vertices at `positions`: nothing for faces
/// sharing an edge, tri_tri_intersect_sharing_vertex for faces sharing a node (both rotated
/// so that it comes first, keeping their winding), tri_tri_intersect otherwise (vertices in the
/// order a, b, c).
[[nodiscard]] TriTriResult face_pair_intersect(const gpu::Face& fa, const gpu::Face& fb,
                                               VertexPositions positions);

}  // namespace deformcd::collision
