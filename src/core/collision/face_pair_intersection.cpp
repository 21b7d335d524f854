#include "core/collision/face_pair_intersection.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "core/collision/tri_tri_primitives.h"

namespace deformcd::collision {

namespace {

std::uint32_t corner(const gpu::Face& f, int i) {
  return face_corner(f, static_cast<std::uint32_t>(i));
}

// Triangle `face` with its vertices rotated so that corner `first` comes first (a rotation
// keeps the winding).
void load_rotated(const gpu::Face& face, int first, VertexPositions positions, glm::vec3 t[3]) {
  for (int i = 0; i < 3; ++i)
    t[i] = vertex_position(positions, face.body, corner(face, (first + i) % 3));
}

}  // namespace

SharedNodes shared_nodes(const gpu::Face& a, const gpu::Face& b) {
  SharedNodes s;
  // Vertex indices are local to a mesh: faces of different meshes share none.
  if (a.body != b.body) return s;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (corner(a, i) != corner(b, j)) continue;
      if (s.count == 0) {
        s.corner_a = i;
        s.corner_b = j;
      }
      ++s.count;
    }
  }
  return s;
}

bool segment_triangle_meet(const glm::vec3& s0, const glm::vec3& s1, const glm::vec3 t[3]) {
  using namespace detail;
  const float l2 = longest_edge2(t);
  const glm::vec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
  const float n_len = glm::length(n);
  if (!(n_len > kTriTriDegenerateTolerance * l2)) return false;
  const glm::vec3 e = s1 - s0;
  const float size = std::sqrt(std::max(l2, glm::dot(e, e)));
  const glm::vec3 u = n / n_len;
  // The plane tolerance of tri_tri_intersect, for the segment's ends.
  const float tol = (kTriTriTolerance + kTriTriRoundoff * l2 / n_len) * size;
  const float d0 = snap_to_zero(glm::dot(u, s0 - t[0]), tol);
  const float d1 = snap_to_zero(glm::dot(u, s1 - t[0]), tol);
  if (same_strict_sign(d0, d1)) return false;

  // On the plane: both ends (crossing an edge, or wholly inside), else the one point on it, an
  // end or the crossing (d0 != d1 there).
  if (d0 == 0.0f && d1 == 0.0f) return segment_in_plane_meets_triangle(s0, s1, t, n, size);
  const glm::vec3 x = d0 == 0.0f ? s0 : (d1 == 0.0f ? s1 : s0 + e * (d0 / (d0 - d1)));
  return segment_in_plane_meets_triangle(x, x, t, n, size);
}

TriTriResult tri_tri_intersect_sharing_vertex(const glm::vec3 p[3], const glm::vec3 q[3]) {
  if (!segment_triangle_meet(p[1], p[2], q) && !segment_triangle_meet(q[1], q[2], p)) return {};
  return tri_tri_intersect(p, q);
}

TriTriResult face_pair_intersect(const gpu::Face& fa, const gpu::Face& fb,
                                 VertexPositions positions) {
  glm::vec3 p[3];
  glm::vec3 q[3];
  face_vertices(positions, fa, p);
  face_vertices(positions, fb, q);
  // Faces of two meshes share no node (indices are local to a mesh): straight to the triangle
  // test, which starts with the same exact box test. (The GLSL mirror keeps one call site of
  // tri_tri_intersect for llvmpipe's sake and finds no shared node instead: the same answer.)
  if (fa.body != fb.body) return tri_tri_intersect(p, q);
  // Most pairs a broad phase hands on (all of them for brute force) have boxes apart: that
  // exact test first, as tri_tri_intersect would, before looking for shared nodes (faces that
  // share one have touching boxes, so no answer changes).
  if (!detail::boxes_touch(p, q)) return {};
  const SharedNodes shared = shared_nodes(fa, fb);
  if (shared.count >= 2) return {};
  if (shared.count == 0) return tri_tri_intersect(p, q);
  load_rotated(fa, shared.corner_a, positions, p);
  load_rotated(fb, shared.corner_b, positions, q);
  return tri_tri_intersect_sharing_vertex(p, q);
}

}  // namespace deformcd::collision
