#version 430
// Wireframe edges (drawn with glPolygonMode GL_LINE): each body's in its own dark colour.
#include "render/faces.glsl"

out vec4 o_colour;

void main() {
  o_colour = vec4(wire_colour(body_of(gl_PrimitiveID)), 1.0);
}
