#version 430
// The contact response's node pass: one invocation per node sums its constraints' corrections
// over its CSR list in list order, each scaled by 1 / the largest active count among the
// constraint's four nodes (gather_correction in src/core/response/contact_constraints.h,
// written out here because GLSL cannot pass a buffer to a function), then applies the sum to
// its own position and velocity and clamps it within its frame-start reach (apply_correction).
// Each invocation reads and writes only its own node's position and velocity.
#include "common/layout.glsl"
#include "response/contact_constraints.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_NODE_VELOCITY) buffer NodeVelocities {
  vec4 velocities[];
};
layout(std430, binding = BINDING_CONTACT_PAIR) readonly buffer ContactPairs {
  ContactPair pairs[];
};
layout(std430, binding = BINDING_CONTACT_CORRECTION) readonly buffer ContactCorrections {
  vec4 corrections[];
};
layout(std430, binding = BINDING_NODE_CONTACT_OFFSET) readonly buffer NodeContactOffsets {
  uint node_contact_offset[];
};
layout(std430, binding = BINDING_NODE_CONTACT_LIST) readonly buffer NodeContactList {
  uint node_contact_list[];
};
layout(std430, binding = BINDING_NODE_CONTACT_COUNT) readonly buffer NodeContactCounts {
  uint node_contact_count[];
};
layout(std430, binding = BINDING_FRAME_START) readonly buffer FrameStarts {
  vec4 frame_start[];
};

uniform uint u_node_count;
uniform float u_h;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= u_node_count) return;  // the last work group reaches past the end
  // gather_correction, line for line.
  const uint begin = node_contact_offset[i];
  const uint end = node_contact_offset[i + 1u];
  precise vec3 sum = vec3(0.0);
  for (uint e = begin; e < end; ++e) {
    const uint slot = node_contact_list[e];
    const vec4 correction = corrections[slot];
    if (!(correction.w > 0.0)) continue;
    const uvec4 nodes = pairs[slot / 4u].nodes;
    uint most = 1u;
    for (uint k = 0u; k < 4u; ++k) {
      const uint count = node_contact_count[nodes[k]];
      most = most < count ? count : most;  // glm::max(most, count)
    }
    precise vec3 share = correction.xyz / float(most);
    sum += share;
  }
  vec4 position = positions[i];
  vec4 velocity = velocities[i];
  apply_correction(position, velocity, sum, frame_start[i], u_h);
  positions[i] = position;
  velocities[i] = velocity;
}
