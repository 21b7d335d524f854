// shaders/collision/tri_tri_intersection.glsl agrees with the C++ narrow phase
// (src/core/collision/tri_tri_intersection.cpp) it mirrors: shaders/test/tri_tri_probe.comp
// runs the GLSL function on ~20,000 pairs, general and adversarial (near-touching, coplanar,
// slivers at the degenerate threshold, other scales), and every answer is compared with the
// C++ one. The mirror performs the same float operations in the same order, so the flags are
// expected to agree exactly and the segments to rounding.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/collision/tri_tri_intersection.h"
#include "deformcd/gl/ssbo.h"
#include "gl/gl_test_context.h"
#include "gpu/gl/compute_program.h"

namespace deformcd::gl {
namespace {

using glm::vec3;

enum class Kind { kGeneral, kNearTouching, kCoplanar, kSliver, kScaled, kHandMade, kCount };
constexpr std::array<const char*, static_cast<int>(Kind::kCount)> kKindNames = {
    "general", "near-touching", "coplanar z=0", "sliver", "scaled", "hand-made"};

struct Pair {
  std::array<vec3, 3> p;
  std::array<vec3, 3> q;
  Kind kind;
};

class PairGenerator {
 public:
  explicit PairGenerator(std::uint32_t seed) : rng_(seed) {}

  vec3 point(float half_width = 1.0f) {
    std::uniform_real_distribution<float> c(-half_width, half_width);
    const float x = c(rng_);
    const float y = c(rng_);
    const float z = c(rng_);
    return {x, y, z};
  }
  float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng_); }

  Pair general() {
    return {{point(), point(), point()}, {point(), point(), point()}, Kind::kGeneral};
  }

  // q's first vertex sits over a point inside p, at a distance of a few kTriTriTolerance x size
  // from p's plane (either side, or on it): the decisions inside and around the uncertain zone.
  Pair near_touching() {
    const std::array<vec3, 3> p = {point(), point(), point()};
    const vec3 n = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
    float u = uniform(0.0f, 1.0f);
    float v = uniform(0.0f, 1.0f);
    if (u + v > 1.0f) {
      u = 1.0f - u;
      v = 1.0f - v;
    }
    const vec3 on_p = p[0] + u * (p[1] - p[0]) + v * (p[2] - p[0]);
    const float offset = uniform(-4e-5f, 4e-5f) * 2.0f;  // size is ~2 here
    const vec3 side = n * uniform(0.2f, 1.0f) * (offset >= 0.0f ? 1.0f : -1.0f);
    return {p,
            {on_p + offset * n, on_p + side + point(0.5f), on_p + side + point(0.5f)},
            Kind::kNearTouching};
  }

  Pair coplanar() {
    auto flat = [this] {
      const vec3 v = point();
      return vec3(v.x, v.y, 0.0f);
    };
    return {{flat(), flat(), flat()}, {flat(), flat(), flat()}, Kind::kCoplanar};
  }

  // q is a sliver whose height is 1e-5 .. 1e-2 of its length: across the degenerate threshold
  // (1e-4) and into the range where the rounding term of the plane tolerance dominates.
  Pair sliver() {
    const std::array<vec3, 3> p = {point(), point(), point()};
    const vec3 a = point();
    const vec3 b = point();
    const vec3 across = glm::normalize(glm::cross(b - a, point()));
    const float height = std::pow(10.0f, uniform(-5.0f, -2.0f)) * glm::length(b - a);
    const vec3 c = 0.5f * (a + b) + uniform(-0.4f, 0.4f) * (b - a) + height * across;
    return {p, {a, b, c}, Kind::kSliver};
  }

  // A general pair at mm or km scale, or offset from the origin.
  Pair scaled() {
    Pair pair = general();
    const float scale = std::pow(10.0f, uniform(-3.0f, 3.0f));
    const vec3 offset = point(10.0f) * scale;
    for (vec3& v : pair.p)
      v = v * scale + offset;
    for (vec3& v : pair.q)
      v = v * scale + offset;
    pair.kind = Kind::kScaled;
    return pair;
  }

 private:
  std::mt19937 rng_;
};

// Cases from tests/core/tri_tri_intersection_test.cpp, each also with the triangles swapped.
std::vector<Pair> hand_made_pairs() {
  const std::array<vec3, 3> base = {vec3(0, 0, 0), vec3(2, 0, 0), vec3(0, 2, 0)};
  const std::vector<std::array<vec3, 3>> others = {
      {vec3(-1, 0.5f, -1), vec3(3, 0.5f, -1), vec3(1, 0.5f, 1)},              // crossing
      {vec3(0, 0, 0.5f), vec3(1, 0, 1), vec3(0, 1, 2)},                       // above
      {vec3(3, 3, -1), vec3(4, 3, -1), vec3(3.5f, 3, 1)},                     // beside
      {vec3(0.5f, 0.5f, 0), vec3(1, 0.5f, 1), vec3(0.5f, 1, 1)},              // vertex touch
      {vec3(0.2f, 0.2f, 0), vec3(1, 0.2f, 0), vec3(0.5f, 0.5f, 1)},           // edge touch
      {vec3(0.5f, 0.5f, 4e-6f), vec3(1, 0.5f, 1), vec3(0.5f, 1, 1)},          // barely
      {vec3(0.5f, 0.5f, 2e-3f), vec3(1, 0.5f, 1), vec3(0.5f, 1, 1)},          // apart
      {vec3(-1, 0.5f, -1e-2f), vec3(3, 0.5f, -1e-2f), vec3(1, 0.5f, 1e-2f)},  // thin
      {vec3(-1, 0.5f, -1e-6f), vec3(3, 0.5f, -1e-6f), vec3(1, 0.5f, 1e-6f)},  // sliver
      {vec3(0.5f, 0.5f, 0), vec3(3, 0.5f, 0), vec3(0.5f, 3, 0)},              // coplanar overlap
      {vec3(3, 3, 0), vec3(5, 3, 0), vec3(3, 5, 0)},                          // coplanar far
      {vec3(1.1f, 1.1f, 0), vec3(1.1f, 3, 0), vec3(3, 1.1f, 0)},              // across hypotenuse
      {vec3(0.2f, 0.2f, 0), vec3(0.6f, 0.2f, 0), vec3(0.2f, 0.6f, 0)},        // inside
      {vec3(-1, 0.5f, -1), vec3(0, 0.5f, 0), vec3(1, 0.5f, 1)},               // collinear
      {vec3(0.5f, 0.5f, 0), vec3(0.5f, 0.5f, 0), vec3(0.5f, 0.5f, 0)},        // point
  };
  std::vector<Pair> pairs;
  for (const float scale : {1e-6f, 1e-3f, 1.0f, 1e3f}) {
    for (const auto& other : others) {
      Pair pair{base, other, Kind::kHandMade};
      for (vec3& v : pair.p)
        v *= scale;
      for (vec3& v : pair.q)
        v *= scale;
      pairs.push_back(pair);
      pairs.push_back({pair.q, pair.p, Kind::kHandMade});
    }
  }
  pairs.push_back({{vec3(1, 1, 1), vec3(1.5f, 1, 1.5f), vec3(1, 1.5f, 1)},
                   {vec3(0, 0, 0), vec3(4, 0, 4), vec3(0, 4, 0)},
                   Kind::kHandMade});  // tilted coplanar, one inside the other
  return pairs;
}

std::vector<Pair> test_pairs() {
  PairGenerator gen(20260522u);
  std::vector<Pair> pairs = hand_made_pairs();
  for (int i = 0; i < 8000; ++i)
    pairs.push_back(gen.general());
  for (int i = 0; i < 4000; ++i)
    pairs.push_back(gen.near_touching());
  for (int i = 0; i < 3000; ++i)
    pairs.push_back(gen.coplanar());
  for (int i = 0; i < 3000; ++i)
    pairs.push_back(gen.sliver());
  for (int i = 0; i < 2000; ++i)
    pairs.push_back(gen.scaled());
  return pairs;
}

struct GpuAnswer {
  bool intersect;
  bool coplanar;
  vec3 segment[2];
};

// Runs shaders/test/tri_tri_probe.comp on every pair.
std::vector<GpuAnswer> run_probe(const std::vector<Pair>& pairs) {
  std::vector<glm::vec4> triangles;
  triangles.reserve(pairs.size() * 6);
  for (const Pair& pair : pairs) {
    for (const vec3& v : pair.p)
      triangles.emplace_back(v, 0.0f);
    for (const vec3& v : pair.q)
      triangles.emplace_back(v, 0.0f);
  }
  const auto count = static_cast<std::uint32_t>(pairs.size());
  ComputeProgram program("test/tri_tri_probe.comp");
  const Ssbo<glm::vec4> input{std::span<const glm::vec4>(triangles)};
  const Ssbo<glm::uvec4> flags(count);
  const Ssbo<glm::vec4> segments(2 * std::size_t{count});
  input.bind(0);
  flags.bind(1);
  segments.bind(2);
  program.set_uniform("u_count", count);
  program.dispatch_covering(count);
  const std::vector<glm::uvec4> flag_out = flags.download();
  const std::vector<glm::vec4> segment_out = segments.download();
  std::vector<GpuAnswer> answers(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    answers[i] = {flag_out[i].x != 0,
                  flag_out[i].y != 0,
                  {vec3(segment_out[2 * i]), vec3(segment_out[2 * i + 1])}};
  }
  return answers;
}

float pair_size(const Pair& pair) {
  float longest = 0.0f;
  for (int i = 0; i < 3; ++i) {
    longest = std::max(longest, glm::length(pair.p[(i + 1) % 3] - pair.p[i]));
    longest = std::max(longest, glm::length(pair.q[(i + 1) % 3] - pair.q[i]));
  }
  return longest;
}

class TriTriGlTest : public test_support::GlTest {};

TEST_F(TriTriGlTest, GlslMirrorMatchesTheCppNarrowPhase) {
  const std::vector<Pair> pairs = test_pairs();
  const std::vector<GpuAnswer> gpu = run_probe(pairs);

  constexpr int kKinds = static_cast<int>(Kind::kCount);
  std::array<int, kKinds> total{};
  std::array<int, kKinds> intersecting{};
  std::array<int, kKinds> coplanar{};
  std::array<int, kKinds> flag_mismatches{};
  std::array<int, kKinds> segment_mismatches{};
  float worst_segment_error = 0.0f;  // relative to the pair's size
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const Pair& pair = pairs[i];
    const int kind = static_cast<int>(pair.kind);
    const collision::TriTriResult cpu = collision::tri_tri_intersect(pair.p.data(), pair.q.data());
    ++total[kind];
    intersecting[kind] += cpu.intersect ? 1 : 0;
    coplanar[kind] += cpu.coplanar ? 1 : 0;
    if (cpu.intersect != gpu[i].intersect || cpu.coplanar != gpu[i].coplanar) {
      ++flag_mismatches[kind];
      ADD_FAILURE() << kKindNames[static_cast<std::size_t>(kind)] << " pair " << i
                    << ": C++ intersect " << cpu.intersect << " coplanar " << cpu.coplanar
                    << ", GLSL intersect " << gpu[i].intersect << " coplanar " << gpu[i].coplanar;
      continue;
    }
    if (!cpu.intersect || cpu.coplanar) continue;
    const float size = pair_size(pair);
    const float error = std::max(glm::length(cpu.segment[0] - gpu[i].segment[0]),
                                 glm::length(cpu.segment[1] - gpu[i].segment[1])) /
                        size;
    worst_segment_error = std::max(worst_segment_error, error);
    if (!(error <= 1e-5f)) {
      ++segment_mismatches[kind];
      ADD_FAILURE() << kKindNames[static_cast<std::size_t>(kind)] << " pair " << i
                    << ": segment endpoints differ by " << error << " x size";
    }
  }
  for (std::size_t k = 0; k < kKinds; ++k) {
    std::printf(
        "[ tri-tri ] %-14s pairs %5d  intersecting %5d  coplanar %5d  flag mismatches %d"
        "  segment mismatches %d\n",
        kKindNames[k], total[k], intersecting[k], coplanar[k], flag_mismatches[k],
        segment_mismatches[k]);
  }
  std::printf("[ tri-tri ] worst segment endpoint difference: %g x size\n",
              static_cast<double>(worst_segment_error));
  // Each kind exercises both answers (the hand-made ones include the degenerate cases).
  for (std::size_t k = 0; k < kKinds; ++k) {
    EXPECT_GT(intersecting[k], 0) << kKindNames[k];
    EXPECT_LT(intersecting[k], total[k]) << kKindNames[k];
  }
  // Coplanar pairs reach the coplanar branch unless their bounding boxes are apart (rejected
  // first, with coplanar unset): every intersecting one is flagged coplanar.
  EXPECT_GE(coplanar[static_cast<int>(Kind::kCoplanar)],
            intersecting[static_cast<int>(Kind::kCoplanar)]);
  EXPECT_GT(coplanar[static_cast<int>(Kind::kCoplanar)], 0);
}

}  // namespace
}  // namespace deformcd::gl
