// The surface the collision shaders read: node positions (SSBO 0, the simulation's) and the
// faces (SSBO 7), both read-only during a collision pass.
#include "common/layout.glsl"

layout(std430, binding = BINDING_NODE_POSITION) readonly buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_FACE_INFO) readonly buffer FaceInfo {
  Face faces[];
};
