// The collision counters (SSBO 23), reset by the host before each pass; every collision shader
// that counts includes this one declaration (an include is expanded once per shader).
#include "common/layout.glsl"

layout(std430, binding = BINDING_COLLISION_COUNTERS) buffer Counters {
  CollisionCounters counters;
};
