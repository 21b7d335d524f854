// The mass-spring step's per-element functions, mirroring src/core/sim/mass_spring.h line for
// line: the same float operations in the same order, dot and cross as glm's, products and sums
// `precise` (no fused multiply-add: llvmpipe fused glm's dot, and 70 % of the nodes' forces
// differed from the CPU's in the last bit), so that the GL and CPU backends agree bit for bit.
// Include common/exact_math.glsl first. Change both files together.
//
// The per-node gathers are not here: GLSL 4.30 cannot pass a buffer to a function, so their
// loops are written out in sim/node_update.comp, again line for line.

// Per-substep constants (sim::SubstepConstants).
struct SubstepConstants {
  float h;               // substep length, s
  vec3 gravity;          // m/s^2
  float velocity_decay;  // exp(-velocity_damping * h), applied to every free node
};

// A spring edge's state (u, q): u the unit vector from a to b and
// q = (length - rest_length) + damping (vb - va) . u, or (0, 0) for a collapsed edge. Every
// spring on the edge exerts (k q) u on node a (spring_term with +k) and the opposite on node b
// (spring_term with -k): Hooke's law along the spring plus stiffness-proportional damping of
// the relative velocity along it (damping in seconds x stiffness).
vec4 spring_edge_state(vec3 xa, vec3 xb, vec3 va, vec3 vb, float rest_length, float damping) {
  const vec3 d = xb - xa;
  const float len = sqrt(exact_dot(d, d));
  if (!(len > 0.0)) return vec4(0.0);
  const vec3 u = d / len;
  precise const float q = (len - rest_length) + damping * exact_dot(vb - va, u);
  return vec4(u, q);
}

// One spring's force on a node from its edge's state (spring_edge_state).
vec3 spring_term(vec4 edge_state, float signed_stiffness) {
  precise const vec3 term = (signed_stiffness * edge_state.w) * edge_state.xyz;
  return term;
}

// A tetrahedron's volume (positive as gpu::Tetra orders its corners) and its gradient
// g[k] = dV/dx_k: what the volume forces below and the response's volume constraints
// (response/contact_constraints.glsl) act along.
float tetrahedron_volume(vec3 x[4], out vec3 g[4]) {
  precise vec3 ab = x[1] - x[0], ac = x[2] - x[0], ad = x[3] - x[0];
  precise vec3 g1 = exact_cross(ac, ad) / 6.0;
  precise vec3 g2 = exact_cross(ad, ab) / 6.0;
  precise vec3 g3 = exact_cross(ab, ac) / 6.0;
  precise vec3 g0 = -(g1 + g2 + g3);
  g = vec3[4](g0, g1, g2, g3);
  precise float volume = exact_dot(ab, g1);
  return volume;
}

// Volume forces on the four corners of tetrahedron (a, b, c, d), from the energy
// c (V - V0)^2 / 2: f_i = -c (V - V0) dV/dx_i, with c = Tetra.stiffness. They sum to zero.
void tet_volume_forces(vec3 a, vec3 b, vec3 c, vec3 d, float rest_volume, float stiffness,
                       out vec3 out0, out vec3 out1, out vec3 out2, out vec3 out3) {
  vec3 g[4];
  const float volume = tetrahedron_volume(vec3[4](a, b, c, d), g);
  precise const float scale = -stiffness * (volume - rest_volume);
  precise const vec3 f1 = scale * g[1];
  precise const vec3 f2 = scale * g[2];
  precise const vec3 f3 = scale * g[3];
  precise const vec3 f0 = -(f1 + f2 + f3);
  out0 = f0;
  out1 = f1;
  out2 = f2;
  out3 = f3;
}

// Semi-implicit (symplectic) Euler for one node: velocity from force and gravity, decayed,
// then position from the new velocity plus the body's carry velocity. `position.w` is the
// inverse mass; 0 marks a fixed node, which keeps zero velocity but is still carried.
void integrate_node(inout vec4 position, inout vec4 velocity, vec3 force, vec3 carry_velocity,
                    SubstepConstants c) {
  const float inverse_mass = position.w;
  precise vec3 v = velocity.xyz;
  if (inverse_mass > 0.0) {
    v = (v + c.h * (force * inverse_mass + c.gravity)) * c.velocity_decay;
  } else {
    v = vec3(0.0);
  }
  velocity = vec4(v, 0.0);
  precise const vec3 moved = position.xyz + c.h * (v + carry_velocity);
  position = vec4(moved, inverse_mass);
}
