#pragma once
// sim::spring_edge_state and sim::tet_volume_forces (src/core/sim/mass_spring.h) for kBatch
// elements at once, in SIMD lanes (std::experimental::simd: SSE on the baseline x86-64 target).
// Each lane performs the scalar function's operations in the same order (glm's dot is
// (x x' + y y') + z z', its cross the usual three differences), and IEEE division, square root,
// products and sums are correctly rounded lane by lane, so the results are bit-identical to the
// scalar functions' (tests/cpu/mass_spring_test.cpp, StepEqualsThePerSpringPassesBitForBit).
// Change the two together.

#include <cstddef>
#include <cstdint>
#include <experimental/simd>

#include <glm/vec4.hpp>

#include "deformcd/gpu_layout.h"

namespace deformcd::cpu {

namespace stdx = std::experimental;

inline constexpr std::size_t kBatch = 4;
using Lanes = stdx::fixed_size_simd<float, kBatch>;

struct Vec3Lanes {
  Lanes x, y, z;
};

inline Vec3Lanes operator-(const Vec3Lanes& a, const Vec3Lanes& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3Lanes operator+(const Vec3Lanes& a, const Vec3Lanes& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3Lanes operator*(const Lanes& s, const Vec3Lanes& a) {
  return {s * a.x, s * a.y, s * a.z};
}
inline Vec3Lanes operator/(const Vec3Lanes& a, const Lanes& s) {
  return {a.x / s, a.y / s, a.z / s};
}
inline Lanes dot(const Vec3Lanes& a, const Vec3Lanes& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;  // glm: (x x' + y y') + z z'
}
inline Vec3Lanes cross(const Vec3Lanes& a, const Vec3Lanes& b) {
  return {a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y};  // as glm
}

/// The xyz of `v[index[lane]]` in each lane.
inline Vec3Lanes gather(const glm::vec4* v, const std::uint32_t* index) {
  return {Lanes([&](auto lane) { return v[index[lane]].x; }),
          Lanes([&](auto lane) { return v[index[lane]].y; }),
          Lanes([&](auto lane) { return v[index[lane]].z; })};
}

/// sim::spring_edge_state for edges [0, kBatch) of the arrays, written to state[0, kBatch).
inline void spring_edge_states(const glm::vec4* positions, const glm::vec4* velocities,
                               const std::uint32_t* a, const std::uint32_t* b,
                               const float* rest_length, const float* damping, glm::vec4* state) {
  const Vec3Lanes xa = gather(positions, a), xb = gather(positions, b);
  const Vec3Lanes d = xb - xa;
  const Lanes length = stdx::sqrt(dot(d, d));
  const Vec3Lanes u = d / length;
  const Vec3Lanes dv = gather(velocities, b) - gather(velocities, a);
  const Lanes q = (length - Lanes(rest_length, stdx::element_aligned)) +
                  Lanes(damping, stdx::element_aligned) * dot(dv, u);
  for (std::size_t lane = 0; lane < kBatch; ++lane) {
    state[lane] =
        length[lane] > 0.0f ? glm::vec4(u.x[lane], u.y[lane], u.z[lane], q[lane]) : glm::vec4(0.0f);
  }
}

/// sim::tet_volume_forces for tetrahedra [0, kBatch) of `tets`, each corner force written to
/// out[slot[4 t + k]] (w = 0).
inline void tet_volume_forces(const glm::vec4* positions, const gpu::Tetra* tets,
                              const std::uint32_t* slot, glm::vec4* out) {
  std::uint32_t corner[4][kBatch];
  for (std::size_t t = 0; t < kBatch; ++t) {
    corner[0][t] = tets[t].a;
    corner[1][t] = tets[t].b;
    corner[2][t] = tets[t].c;
    corner[3][t] = tets[t].d;
  }
  const Vec3Lanes a = gather(positions, corner[0]);
  const Vec3Lanes ab = gather(positions, corner[1]) - a;
  const Vec3Lanes ac = gather(positions, corner[2]) - a;
  const Vec3Lanes ad = gather(positions, corner[3]) - a;
  const Lanes six(6.0f);
  const Vec3Lanes grad_b = cross(ac, ad) / six;
  const Vec3Lanes grad_c = cross(ad, ab) / six;
  const Vec3Lanes grad_d = cross(ab, ac) / six;
  const Lanes volume = dot(ab, grad_b);
  const Lanes rest([&](auto t) { return tets[t].rest_volume; });
  const Lanes stiffness([&](auto t) { return tets[t].stiffness; });
  const Lanes scale = -stiffness * (volume - rest);
  const Vec3Lanes f1 = scale * grad_b;
  const Vec3Lanes f2 = scale * grad_c;
  const Vec3Lanes f3 = scale * grad_d;
  const Vec3Lanes sum = f1 + f2 + f3;
  const Vec3Lanes f0{-sum.x, -sum.y, -sum.z};
  for (std::size_t t = 0; t < kBatch; ++t) {
    const std::uint32_t* s = slot + 4 * t;
    out[s[0]] = glm::vec4(f0.x[t], f0.y[t], f0.z[t], 0.0f);
    out[s[1]] = glm::vec4(f1.x[t], f1.y[t], f1.z[t], 0.0f);
    out[s[2]] = glm::vec4(f2.x[t], f2.y[t], f2.z[t], 0.0f);
    out[s[3]] = glm::vec4(f3.x[t], f3.y[t], f3.z[t], 0.0f);
  }
}

}  // namespace deformcd::cpu
