#version 430
// Every surface face of every body, as one indexed draw: the node positions come straight from
// the simulation's SSBO 0 bound as a vertex buffer (vec4: xyz, then the inverse mass, unused
// here), the indices from the world's face list in its order, so that gl_PrimitiveID in the
// fragment shaders is the global face index (see render/faces.glsl).

layout(location = 0) in vec4 a_position;

uniform mat4 u_view;
uniform mat4 u_projection;

out vec3 v_view_position;  // for flat normals from derivatives (render/shaded.frag)

void main() {
  const vec4 view_position = u_view * vec4(a_position.xyz, 1.0);
  v_view_position = view_position.xyz;
  gl_Position = u_projection * view_position;
}
