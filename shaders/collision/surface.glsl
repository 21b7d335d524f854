// The surfaces the collision shaders read: the faces (SSBO 7, vertex indices local to their
// mesh, Face.body the mesh) and the vertex positions (SSBO 0), both read-only during a pass.
//
// Positions are float words, not vec4s: the buffer is the caller's (a simulation's vec4 per
// node, a renderer's packed xyz...) or the backend's gathered copy, and each mesh says where its
// vertices start and how far apart they are (MeshInfo.position_offset, position_stride, in
// floats). vertex_position mirrors collision::vertex_position (vertex_positions.h): change both
// together.
#include "collision/meshes.glsl"
#include "common/layout.glsl"

layout(std430, binding = BINDING_NODE_POSITION) readonly buffer VertexWords {
  float vertex_words[];
};
layout(std430, binding = BINDING_FACE_INFO) readonly buffer FaceInfo {
  Face faces[];
};

// Mesh `mesh`'s (position_offset, position_stride): loaded once for a face's three vertices.
uvec2 vertex_layout(uint mesh) {
  return uvec2(meshes[mesh].position_offset, meshes[mesh].position_stride);
}

// Vertex v of the mesh whose vertex_layout is `at`.
vec3 vertex_at(uvec2 at, uint v) {
  const uint w = at.x + v * at.y;
  return vec3(vertex_words[w], vertex_words[w + 1u], vertex_words[w + 2u]);
}

vec3 vertex_position(uint mesh, uint v) {
  return vertex_at(vertex_layout(mesh), v);
}
