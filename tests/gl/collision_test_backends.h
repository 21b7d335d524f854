#pragma once
// What the GL collision tests share: a GL collision backend over a fixture's meshes, positions
// in GL buffers the test owns (as a caller's VBO would hold them), and comparisons of face
// pairs with host references.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/collision/collision_backend.h"
#include "deformcd/gl/context.h"
#include "deformcd/gl/ssbo.h"
#include "deformcd/gpu_layout.h"
#include "gl/collision_test_worlds.h"
#include "gpu/gl/gl_collision.h"
#include "support/collision_fixtures.h"

namespace deformcd::test {

using collision::PositionSource;

/// Same pairs in the same order (both sorted), segments bit for bit.
inline void expect_same_pairs(const std::vector<gpu::FacePair>& actual,
                              const std::vector<gpu::FacePair>& expected, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    const gpu::FacePair& x = actual[i];
    const gpu::FacePair& y = expected[i];
    ASSERT_EQ(x.face_a, y.face_a) << "pair " << i;
    ASSERT_EQ(x.face_b, y.face_b) << "pair " << i;
    EXPECT_EQ(x.coplanar, y.coplanar) << "faces " << x.face_a << ", " << x.face_b;
    EXPECT_EQ(x.segment0, y.segment0) << "faces " << x.face_a << ", " << x.face_b;
    EXPECT_EQ(x.segment1, y.segment1) << "faces " << x.face_a << ", " << x.face_b;
  }
}

/// Flag 1 on every face of `pairs`, 0 elsewhere.
inline std::vector<std::uint32_t> flags_of(const std::vector<gpu::FacePair>& pairs,
                                           std::size_t face_count) {
  std::vector<std::uint32_t> flags(face_count, 0u);
  for (const gpu::FacePair& p : pairs)
    flags[p.face_a] = flags[p.face_b] = 1u;
  return flags;
}

/// Every body's positions in a simulation's GL position buffer (vec4 per node, body b's from its
/// node_offset), as a World hands them to its detector.
inline std::vector<collision::PositionSource> simulation_sources(
    std::uint32_t buffer, const std::vector<gpu::ObjectInfo>& objects) {
  std::vector<collision::PositionSource> sources;
  for (const gpu::ObjectInfo& o : objects) {
    collision::PositionSource s;
    s.kind = collision::PositionSource::Kind::kGl;
    s.gl_buffer = buffer;
    s.offset_bytes = std::uint64_t{o.node_offset} * sizeof(glm::vec4);
    s.stride_bytes = sizeof(glm::vec4);
    s.vertex_count = o.node_count;
    sources.push_back(s);
  }
  return sources;
}

inline std::uint32_t count_set(const std::vector<std::uint32_t>& flags) {
  std::uint32_t n = 0;
  for (std::uint32_t f : flags)
    n += f != 0 ? 1u : 0u;
  return n;
}

/// Positions of some meshes in one GL buffer the test owns: from `offset_bytes`, mesh after
/// mesh, vertex after vertex `stride_bytes` apart (12: packed xyz). The bytes between vertices
/// and before the first hold NaN, so that a shader reading the wrong words finds no contact.
class GlPositionBuffer {
 public:
  GlPositionBuffer(const std::vector<std::vector<glm::vec4>>& meshes, std::size_t offset_bytes,
                   std::size_t stride_bytes)
      : buffer_(bytes_for(meshes, offset_bytes, stride_bytes)), stride_(stride_bytes) {
    std::size_t at = offset_bytes;
    for (const std::vector<glm::vec4>& m : meshes) {
      offsets_.push_back(at);
      counts_.push_back(static_cast<std::uint32_t>(m.size()));
      at += m.size() * stride_bytes;
    }
    write(meshes);
  }

  /// Rewrites every mesh's positions (as many as at construction).
  void write(const std::vector<std::vector<glm::vec4>>& meshes) {
    std::vector<float> words(buffer_.size_bytes() / sizeof(float),
                             std::numeric_limits<float>::quiet_NaN());
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      for (std::size_t i = 0; i < meshes[m].size(); ++i) {
        float* w = &words[(offsets_[m] + i * stride_) / sizeof(float)];
        w[0] = meshes[m][i].x;
        w[1] = meshes[m][i].y;
        w[2] = meshes[m][i].z;
      }
    }
    buffer_.upload(words.data(), words.size() * sizeof(float));
  }

  /// Overwrites one coordinate of one vertex.
  void write_coordinate(std::size_t mesh, std::uint32_t vertex, int axis, float value) {
    buffer_.upload(&value, sizeof(float), offsets_[mesh] + vertex * stride_ + axis * sizeof(float));
  }

  /// Mesh `mesh` (in construction order) as a source.
  [[nodiscard]] PositionSource source(std::size_t mesh) const {
    PositionSource s;
    s.kind = PositionSource::Kind::kGl;
    s.gl_buffer = buffer_.name();
    s.offset_bytes = offsets_[mesh];
    s.stride_bytes = stride_;
    s.vertex_count = counts_[mesh];
    return s;
  }
  [[nodiscard]] std::vector<PositionSource> sources() const {
    std::vector<PositionSource> all;
    for (std::size_t m = 0; m < offsets_.size(); ++m)
      all.push_back(source(m));
    return all;
  }
  [[nodiscard]] std::uint32_t name() const { return buffer_.name(); }

 private:
  static std::size_t bytes_for(const std::vector<std::vector<glm::vec4>>& meshes,
                               std::size_t offset_bytes, std::size_t stride_bytes) {
    std::size_t bytes = offset_bytes;
    for (const std::vector<glm::vec4>& m : meshes)
      bytes += m.size() * stride_bytes;
    return bytes;
  }

  gl::BufferObject buffer_;
  std::size_t stride_;
  std::vector<std::size_t> offsets_;
  std::vector<std::uint32_t> counts_;
};

/// A GL collision backend over bodies' surfaces (test::collision_fixture), reading the
/// fixture's host arrays until told otherwise.
struct GlBackend {
  CollisionFixture fixture;
  gl::GlCollision collision;

  GlBackend(gl::Context& context, const std::vector<BodyInit>& bodies,
            const gl::GlCollisionOptions& options = {}, bool self_collision = false)
      : fixture(collision_fixture(bodies, self_collision)), collision(context, options) {
    collision.set_positions(fixture.host_sources());
    collision.upload(fixture.data);
  }

  /// One pass, its face pairs sorted.
  std::vector<gpu::FacePair> pairs(BroadPhase method) {
    collision.detect(method);
    std::vector<gpu::FacePair> out;
    collision.download_face_pairs(out);
    return sorted(out);
  }

  /// What the host finds on the fixture's current positions.
  [[nodiscard]] std::vector<gpu::FacePair> expected() const { return all_pairs_on_host(fixture); }
};

}  // namespace deformcd::test
