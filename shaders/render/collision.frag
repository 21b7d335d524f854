#version 430
// The colliding faces, filled in their body's collision colour; every other face is discarded.
#include "render/faces.glsl"

out vec4 o_colour;

void main() {
  if (!face_collides(gl_PrimitiveID)) discard;
  o_colour = vec4(collision_colour(body_of(gl_PrimitiveID)), 1.0);
}
