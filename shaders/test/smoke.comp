#version 430
// Smoke test: each invocation writes a known function of its global index. The buffer is longer
// than u_count so the test can also see that the bounds guard keeps the tail untouched.

layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer Values {
  uint values[];
};

uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;  // the last work group reaches past u_count
  values[i] = i * i + 7u;    // wraps modulo 2^32, as uint arithmetic does in C++
}
