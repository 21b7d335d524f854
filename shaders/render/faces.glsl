// What the fragment shaders know about the face they draw, indexed by gl_PrimitiveID (the
// global face index: surface.vert draws the world's faces in order, in one call).
//   face_flags: the collision pass's result (the paper's SSBO 5), nonzero when the face is in
//               a contact; read on the GPU, never copied to the CPU.
//   face_body:  the body of each face, uploaded once by the renderer.
// The renderer reads the binding points back from the linked program, so they are set here
// only.
#include "common/layout.glsl"

#define BINDING_RENDER_FACE_BODY 25  // past the simulation's and collision's bindings

layout(std430, binding = BINDING_COLLISION_RESULT) readonly buffer CollisionResult {
  uint face_flags[];
};
layout(std430, binding = BINDING_RENDER_FACE_BODY) readonly buffer FaceBody {
  uint face_body[];
};

uniform bool u_show_collisions;  // false: the flags are stale (no collision pass) or unwanted

bool face_collides(int face) {
  return u_show_collisions && face_flags[face] != 0u;
}

uint body_of(int face) {
  return face_body[face];
}

// The paper's colours (Figs. 8-10): object 1's colliding faces red, object 2's blue; any
// further body's green.
vec3 collision_colour(uint body) {
  if (body == 0u) return vec3(1.0, 0.0, 0.0);
  if (body == 1u) return vec3(0.0, 0.0, 1.0);
  return vec3(0.0, 0.8, 0.0);
}

// Dark edge colours, one per body (cycling), far from the collision colours.
vec3 wire_colour(uint body) {
  const vec3 palette[4] = vec3[4](vec3(0.18, 0.18, 0.20), vec3(0.36, 0.26, 0.12),
                                  vec3(0.10, 0.30, 0.28), vec3(0.30, 0.12, 0.30));
  return palette[body % 4u];
}

// Light surface colours for the shaded mode, one per body (cycling).
vec3 surface_colour(uint body) {
  const vec3 palette[4] = vec3[4](vec3(0.82, 0.80, 0.74), vec3(0.72, 0.78, 0.84),
                                  vec3(0.76, 0.84, 0.74), vec3(0.84, 0.76, 0.82));
  return palette[body % 4u];
}
