// glm's dot and cross written out, with every product and sum `precise`, so that a driver can
// neither fuse a * b + c into one fma nor reorder the sums: the GLSL mirrors of the CPU's
// per-element functions (narrow phase, contact response) compute what glm computes, bit for bit.
// Include after #version: #include "common/exact_math.glsl".

// glm::dot: the products, then (x + y) + z.
float exact_dot(vec3 a, vec3 b) {
  precise vec3 t = a * b;
  precise float r = (t.x + t.y) + t.z;
  return r;
}

// glm::cross.
vec3 exact_cross(vec3 x, vec3 y) {
  precise vec3 r = vec3(x.y * y.z - y.y * x.z, x.z * y.x - y.z * x.x, x.x * y.y - y.x * x.y);
  return r;
}
