#version 430
// Writes the arguments of a glDispatchComputeIndirect from a count the previous shaders took
// with atomicAdd, so that no count is read back to the host inside a pass. One invocation.
// The consumer covers min(count, u_capacity) list entries along axis u_count_axis (0: x, 1: y)
// with work groups of u_local_size invocations on that axis, at most u_max_groups of them (the
// consumer loops over the rest, grid-stride), and u_other_groups work groups on the other axis.
#include "collision/counters.glsl"
#include "collision/gl_work_buffers.glsl"
#include "common/layout.glsl"

layout(local_size_x = 1) in;

layout(std430, binding = BINDING_DISPATCH_ARGS) buffer DispatchArgs {
  uint dispatch_args[];  // see collision/gl_work_buffers.glsl
};

uniform uint u_source;  // 0: counters.box_pairs, 1: counters.candidates, 2: the touching pairs
uniform uint u_capacity;      // entries the list holds: the count past it was not stored
uniform uint u_count_axis;    // 0: the list runs along x, 1: along y
uniform uint u_local_size;    // the consumer's local size along that axis
uniform uint u_max_groups;    // the device's work-group limit along that axis
uniform uint u_other_groups;  // work groups along the other axis
uniform uint u_args_offset;   // where the triple goes, in uints

void main() {
  const uint counted = u_source == 0u   ? counters.box_pairs
                       : u_source == 1u ? counters.candidates
                                        : dispatch_args[DISPATCH_ARGS_TOUCHING];
  const uint count = min(counted, u_capacity);
  // Written to avoid overflowing near 2^32.
  const uint groups = min(count / u_local_size + (count % u_local_size != 0u ? 1u : 0u),
                          u_max_groups);
  dispatch_args[u_args_offset] = u_count_axis == 0u ? groups : u_other_groups;
  dispatch_args[u_args_offset + 1u] = u_count_axis == 0u ? u_other_groups : groups;
  dispatch_args[u_args_offset + 2u] = 1u;
}
