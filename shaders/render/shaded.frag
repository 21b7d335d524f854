#version 430
// Lit faces in their body's colour, colliding faces in their collision colour (unlit, so the
// image shows the paper's exact colours).
#include "render/faces.glsl"

in vec3 v_view_position;

out vec4 o_colour;

void main() {
  const int face = gl_PrimitiveID;
  if (face_collides(face)) {
    o_colour = vec4(collision_colour(body_of(face)), 1.0);
    return;
  }
  // The flat normal from the derivatives of the view-space position: constant over each
  // triangle and always that of the current, deformed positions (no normal buffer to update).
  vec3 normal = normalize(cross(dFdx(v_view_position), dFdy(v_view_position)));
  const vec3 to_eye = normalize(-v_view_position);
  // Faces can be seen from behind where bodies interpenetrate; light them as their front.
  if (dot(normal, to_eye) < 0.0) normal = -normal;
  const vec3 key = normalize(vec3(0.4, 0.7, 0.6));  // view space: above, right, in front
  const float light = 0.25 + 0.55 * max(dot(normal, key), 0.0) + 0.25 * dot(normal, to_eye);
  o_colour = vec4(surface_colour(body_of(face)) * min(light, 1.0), 1.0);
}
