#pragma once
// The mass-spring step as pure per-element functions: one spring (the paper's SpringUpdate),
// one node's force gather (NodeForce) and one node's integration (NodeUpdate). The CPU backend
// calls these; shaders/sim/*.comp mirror them line for line, so both backends compute the same
// floating-point operations in the same order.

#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "deformcd/gpu_layout.h"

namespace deformcd::sim {

/// Per-substep constants.
struct SubstepConstants {
  float h;               ///< substep length, s
  glm::vec3 gravity;     ///< m/s^2
  float velocity_decay;  ///< exp(-velocity_damping * h), applied to every free node
};

/// Force on spring end a (end b gets the opposite): Hooke's law along the spring plus damping
/// of the relative velocity along it, stiffness-proportional: the damping coefficient is
/// `damping` (seconds) x stiffness. A collapsed spring (zero length) exerts no force.
inline glm::vec3 spring_force(const glm::vec3& xa, const glm::vec3& xb, const glm::vec3& va,
                              const glm::vec3& vb, float rest_length, float stiffness,
                              float damping) {
  const glm::vec3 d = xb - xa;
  const float length = std::sqrt(glm::dot(d, d));
  if (!(length > 0.0f)) return glm::vec3(0.0f);
  const glm::vec3 u = d / length;
  const float magnitude = stiffness * ((length - rest_length) + damping * glm::dot(vb - va, u));
  return magnitude * u;
}

/// spring_force in two parts, for a backend that computes each edge once for all the springs on
/// it (node_force_lists.h): the edge's state (u, q), u the unit vector from a to b and
/// q = (length - rest_length) + damping (vb - va) . u, or (0, 0) for a collapsed edge; then each
/// spring's term (signed_stiffness q) u. With signed_stiffness = stiffness the term equals
/// spring_force(...) bit for bit (the same operations on the same operands); with -stiffness,
/// or with a and b swapped, its exact negation. shaders/sim/mass_spring.glsl mirrors both.
inline glm::vec4 spring_edge_state(const glm::vec3& xa, const glm::vec3& xb, const glm::vec3& va,
                                   const glm::vec3& vb, float rest_length, float damping) {
  const glm::vec3 d = xb - xa;
  const float length = std::sqrt(glm::dot(d, d));
  if (!(length > 0.0f)) return glm::vec4(0.0f);
  const glm::vec3 u = d / length;
  return glm::vec4(u, (length - rest_length) + damping * glm::dot(vb - va, u));
}

/// One spring's force on a node from its edge's state (spring_edge_state).
inline glm::vec3 spring_term(const glm::vec4& edge_state, float signed_stiffness) {
  return (signed_stiffness * edge_state.w) * glm::vec3(edge_state);
}

/// A tetrahedron's volume (positive for corners ordered as gpu::Tetra orders them) and its
/// gradient g[k] = dV/dx_k (the four sum to zero): what the volume forces below and the
/// response's volume constraints (src/core/response/contact_constraints.h) act along.
inline float tetrahedron_volume(const glm::vec3 x[4], glm::vec3 g[4]) {
  const glm::vec3 ab = x[1] - x[0], ac = x[2] - x[0], ad = x[3] - x[0];
  g[1] = glm::cross(ac, ad) / 6.0f;
  g[2] = glm::cross(ad, ab) / 6.0f;
  g[3] = glm::cross(ab, ac) / 6.0f;
  g[0] = -(g[1] + g[2] + g[3]);
  return glm::dot(ab, g[1]);
}

/// Volume forces on the four corners of tetrahedron (a, b, c, d), from the energy
/// c (V - V0)^2 / 2: f_i = -c (V - V0) dV/dx_i, with c = gpu::Tetra::stiffness. They sum to
/// zero (no net force) and push an inverted tetrahedron back through its base, which edge
/// springs alone never do.
inline void tet_volume_forces(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                              const glm::vec3& d, float rest_volume, float stiffness,
                              glm::vec3 out[4]) {
  const glm::vec3 x[4] = {a, b, c, d};
  glm::vec3 g[4];
  const float volume = tetrahedron_volume(x, g);
  const float scale = -stiffness * (volume - rest_volume);
  out[1] = scale * g[1];
  out[2] = scale * g[2];
  out[3] = scale * g[3];
  out[0] = -(out[1] + out[2] + out[3]);
}

/// Sum of the tetrahedron volume forces on one node, over its CSR list of corner slots.
inline glm::vec3 gather_tet_force(const std::uint32_t* list, std::uint32_t begin, std::uint32_t end,
                                  const glm::vec4* tet_forces) {
  glm::vec3 sum(0.0f);
  for (std::uint32_t e = begin; e < end; ++e)
    sum += glm::vec3(tet_forces[list[e]]);
  return sum;
}

/// Sum of the spring forces on one node, over its CSR list in order: entry +(s+1) means the
/// node is end a of spring s (force +f), -(s+1) end b (force -f).
inline glm::vec3 gather_node_force(const std::int32_t* list, std::uint32_t begin, std::uint32_t end,
                                   const glm::vec4* spring_forces) {
  glm::vec3 sum(0.0f);
  for (std::uint32_t e = begin; e < end; ++e) {
    const std::int32_t tag = list[e];
    const glm::vec3 f(spring_forces[(tag > 0 ? tag : -tag) - 1]);
    sum += tag > 0 ? f : -f;
  }
  return sum;
}

/// Semi-implicit (symplectic) Euler for one node: velocity from force and gravity, decayed,
/// then position from the new velocity plus the body's carry velocity. `position.w` is the
/// inverse mass; 0 marks a fixed node, which keeps zero velocity but is still carried.
inline void integrate_node(glm::vec4& position, glm::vec4& velocity, const glm::vec3& force,
                           const glm::vec3& carry_velocity, const SubstepConstants& c) {
  const float inverse_mass = position.w;
  glm::vec3 v(velocity);
  if (inverse_mass > 0.0f) {
    v = (v + c.h * (force * inverse_mass + c.gravity)) * c.velocity_decay;
  } else {
    v = glm::vec3(0.0f);
  }
  velocity = glm::vec4(v, 0.0f);
  position = glm::vec4(glm::vec3(position) + c.h * (v + carry_velocity), inverse_mass);
}

}  // namespace deformcd::sim
