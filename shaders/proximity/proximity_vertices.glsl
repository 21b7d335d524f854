// The vertices of the proximity search, mirroring src/core/collision/proximity.h line for line:
// each vertex's motion and reach (per vertex, mesh by mesh, found through vertex_first[mesh]),
// vertex_motion, swept_face_vertices, face_reaches, reach_box and sweep_face. Only exact
// operations happen here (min / max as glm's, one addition per swept corner, one subtraction or
// addition per grown bound), so the boxes are the CPU's bit for bit. Change both files together.
#include "collision/surface.glsl"
#include "common/layout.glsl"
#include "proximity/proximity_buffers.glsl"

layout(std430, binding = BINDING_PROXIMITY_MOTION) readonly buffer VertexMotion {
  vec4 vertex_motion_reach[];  // xyz: the motion over the period (m); w: the reach (m)
};
layout(std430, binding = BINDING_PROXIMITY_VERTEX_FIRST) readonly buffer VertexFirst {
  uint vertex_first[];
};

// glm::min / glm::max per component (b < a ? b : a, a < b ? b : a), and on floats.
vec3 proximity_min(vec3 a, vec3 b) {
  return vec3(b.x < a.x ? b.x : a.x, b.y < a.y ? b.y : a.y, b.z < a.z ? b.z : a.z);
}
vec3 proximity_max(vec3 a, vec3 b) {
  return vec3(a.x < b.x ? b.x : a.x, a.y < b.y ? b.y : a.y, a.z < b.z ? b.z : a.z);
}
float proximity_max(float a, float b) { return a < b ? b : a; }

// collision::face_corner.
uint face_corner(Face f, uint k) { return k == 0u ? f.a : (k == 1u ? f.b : f.c); }

// reach_box of 2, 4 and 6 points: their box grown by `reach` on every side.
Box reach_box2(vec3 p[2], float reach) {
  const vec3 lo = proximity_min(p[0], p[1]), hi = proximity_max(p[0], p[1]);
  return Box(vec4(lo - reach, 0.0), vec4(hi + reach, 0.0));
}
Box reach_box4(vec3 p[4], float reach) {
  vec3 lo = p[0], hi = p[0];
  for (uint i = 1u; i < 4u; ++i) {
    lo = proximity_min(lo, p[i]);
    hi = proximity_max(hi, p[i]);
  }
  return Box(vec4(lo - reach, 0.0), vec4(hi + reach, 0.0));
}
Box reach_box6(vec3 p[6], float reach) {
  vec3 lo = p[0], hi = p[0];
  for (uint i = 1u; i < 6u; ++i) {
    lo = proximity_min(lo, p[i]);
    hi = proximity_max(hi, p[i]);
  }
  return Box(vec4(lo - reach, 0.0), vec4(hi + reach, 0.0));
}

// vertex_motion and the vertex's reach: vertex v of mesh `mesh`.
vec4 vertex_motion_and_reach(uint mesh, uint v) {
  return vertex_motion_reach[vertex_first[mesh] + v];
}

// swept_face_vertices: face f's corners where the period starts (x[0..2], a, b, c) and where
// their motion takes them (x[3..5]).
void swept_face_vertices(Face f, out vec3 x[6]) {
  const uvec2 at = vertex_layout(f.body);
  x[0] = vertex_at(at, f.a);
  x[1] = vertex_at(at, f.b);
  x[2] = vertex_at(at, f.c);
  for (uint k = 0u; k < 3u; ++k) {
    precise vec3 end = x[k] + vertex_motion_and_reach(f.body, face_corner(f, k)).xyz;
    x[3u + k] = end;
  }
}

// face_reaches: the reach of face f's corners (r[0..2]) and the face's (the largest, returned).
float face_reaches(Face f, out float r[3]) {
  r[0] = vertex_motion_and_reach(f.body, f.a).w;
  r[1] = vertex_motion_and_reach(f.body, f.b).w;
  r[2] = vertex_motion_and_reach(f.body, f.c).w;
  return proximity_max(r[0], proximity_max(r[1], r[2]));
}

// SweptFace: a face over the period (its corners at the period's start and end, their
// reaches, its box grown by the largest).
struct SweptFace {
  vec3 x[6];         // corners a, b, c at the period's start, then at its end
  float reach[3];    // the corners' reaches
  float face_reach;  // the largest of them
  Box box;           // x[0..5] grown by face_reach
};

// sweep_face: face f swept over the period.
SweptFace sweep_face(Face f) {
  SweptFace s;
  swept_face_vertices(f, s.x);
  s.face_reach = face_reaches(f, s.reach);
  s.box = reach_box6(s.x, s.face_reach);
  return s;
}

// SweptPrimitives: the boxes of a swept face's primitives.
struct SweptPrimitives {
  Box vertex_box[3];  // corner k's path (x[k], x[3 + k]) grown by its reach
  Box edge_box[3];    // edge k (corner k to (k + 1) % 3): its corners' paths, grown by the larger
};

// kNextCorner: corner (k + 1) % 3, the other end of edge k.
const uint NEXT_CORNER[3] = uint[3](1u, 2u, 0u);

// sweep_primitives: the primitive boxes of swept face s.
SweptPrimitives sweep_primitives(SweptFace s) {
  SweptPrimitives p;
  vec3 lo[3], hi[3];
  for (uint k = 0u; k < 3u; ++k) {
    lo[k] = proximity_min(s.x[k], s.x[3u + k]);
    hi[k] = proximity_max(s.x[k], s.x[3u + k]);
    p.vertex_box[k] = Box(vec4(lo[k] - s.reach[k], 0.0), vec4(hi[k] + s.reach[k], 0.0));
  }
  for (uint k = 0u; k < 3u; ++k) {
    const uint k1 = NEXT_CORNER[k];
    const float r = proximity_max(s.reach[k], s.reach[k1]);
    p.edge_box[k] = Box(vec4(proximity_min(lo[k], lo[k1]) - r, 0.0),
                        vec4(proximity_max(hi[k], hi[k1]) + r, 0.0));
  }
  return p;
}
