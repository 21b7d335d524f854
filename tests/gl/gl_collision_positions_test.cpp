// Where GlCollision reads positions from: a caller's GL buffer at a byte offset with a vec3 or
// vec4 stride, read in place, gives bit for bit the pairs host arrays give; meshes in several GL
// buffers, or mixed with host arrays, are gathered on the GPU and give the same; positions
// rewritten between passes are what the next pass sees; read_positions and find_non_finite read
// the sources; a buffer deleted or shrunk since set_positions is refused, naming the mesh and
// the buffer, and the last results stay.

#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "deformcd/error.h"
#include "gl/collision_test_backends.h"
#include "gl/collision_test_worlds.h"
#include "gl/gl_test_context.h"
#include "gpu/gl/gl_collision.h"

namespace deformcd::gl {
namespace {

using collision::PositionSource;
using test::expect_same_pairs;
using test::GlBackend;
using test::GlPositionBuffer;

constexpr BroadPhase kEveryMethod[] = {BroadPhase::kOctree, BroadPhase::kBrute,
                                       BroadPhase::kOctreeCompact, BroadPhase::kBvh};

// Every method's pairs, flags and counters with the backend's current sources equal those with
// the fixture's host arrays (the reference run of `reference`, same fixture).
void expect_same_as_host(GlBackend& gl, GlBackend& reference, const std::string& what) {
  for (BroadPhase method : kEveryMethod) {
    const std::string name = what + ", " + std::string(broadphase_name(method));
    expect_same_pairs(gl.pairs(method), reference.pairs(method), name);
    const gpu::CollisionCounters a = gl.collision.counters();
    const gpu::CollisionCounters b = reference.collision.counters();
    EXPECT_EQ(a.face_pairs, b.face_pairs) << name;
    EXPECT_EQ(a.box_pairs, b.box_pairs) << name;
    EXPECT_EQ(a.colliding_faces, b.colliding_faces) << name;
    EXPECT_EQ(a.candidates, b.candidates) << name;
    std::vector<std::uint32_t> flags;
    std::vector<std::uint32_t> reference_flags;
    gl.collision.download_face_flags(flags);
    reference.collision.download_face_flags(reference_flags);
    EXPECT_EQ(flags, reference_flags) << name;
  }
}

class GlCollisionPositionsTest : public test_support::GlTest {};

TEST_F(GlCollisionPositionsTest, OneGlBufferWithAnOffsetAndAVec3StrideIsReadInPlace) {
  GlBackend reference(context(), test::three_crossing_grids());
  GlBackend gl(context(), test::three_crossing_grids());
  ASSERT_GT(reference.expected().size(), 10u);
  for (std::size_t stride : {12u, 16u, 20u}) {
    const std::string what = "stride " + std::to_string(stride);
    GlPositionBuffer buffer(gl.fixture.positions, 36, stride);
    gl.collision.set_positions(buffer.sources());
    expect_same_as_host(gl, reference, what);
    EXPECT_TRUE(gl.collision.positions_in_place()) << what;
    std::vector<gpu::MeshInfo> meshes;
    gl.collision.download_meshes(meshes);
    const auto words = static_cast<std::uint32_t>(stride / 4);
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      EXPECT_EQ(meshes[m].position_offset, buffer.source(m).offset_bytes / 4) << what;
      EXPECT_EQ(meshes[m].position_stride, words) << what;
    }
  }
  EXPECT_FALSE(reference.collision.positions_in_place());
}

TEST_F(GlCollisionPositionsTest, MeshesInSeveralBuffersAreGatheredAndGiveTheSamePairs) {
  GlBackend reference(context(), test::three_crossing_grids());
  GlBackend gl(context(), test::three_crossing_grids());
  const std::vector<std::vector<glm::vec4>>& p = gl.fixture.positions;
  GlPositionBuffer shared(p, 16, 12);
  GlPositionBuffer first({p[0]}, 0, 16);
  GlPositionBuffer rest({p[1], p[2]}, 48, 12);
  gl.collision.set_positions({first.source(0), rest.source(0), rest.source(1)});
  expect_same_as_host(gl, reference, "two buffers");
  EXPECT_FALSE(gl.collision.positions_in_place());
  // One buffer for all: in place, the same again.
  gl.collision.set_positions(shared.sources());
  expect_same_as_host(gl, reference, "one buffer");
  EXPECT_TRUE(gl.collision.positions_in_place());
  // A host array among GL buffers: gathered too.
  std::vector<PositionSource> mixed = shared.sources();
  mixed[1] = gl.fixture.host_sources()[1];
  gl.collision.set_positions(mixed);
  expect_same_as_host(gl, reference, "a host array and a buffer");
  EXPECT_FALSE(gl.collision.positions_in_place());
  std::vector<gpu::MeshInfo> meshes;
  gl.collision.download_meshes(meshes);
  EXPECT_EQ(meshes[0].position_offset, 0u);
  EXPECT_EQ(meshes[0].position_stride, 3u);
  EXPECT_EQ(meshes[1].position_offset, 3 * 63 + 3) << "mesh 0's 64 packed vertices before it";
  EXPECT_EQ(meshes[1].position_stride, 4u) << "the host array's stride, kept";
}

// Each pass reads the positions as they are: rewritten in the caller's buffer (in place) or in
// two buffers (gathered anew), the next pass finds the new pairs.
TEST_F(GlCollisionPositionsTest, PositionsRewrittenBetweenPassesAreTheNextPasss) {
  GlBackend gl(context(), test::two_crossing_grids());
  test::CollisionFixture moved = test::collision_fixture(test::two_crossing_grids());
  test::jiggle(moved, 0.02f, 5);
  const std::vector<gpu::FacePair> before = gl.expected();
  const std::vector<gpu::FacePair> after = test::all_pairs_on_host(moved);
  ASSERT_FALSE(before.empty());
  bool differ = before.size() != after.size();
  for (std::size_t i = 0; !differ && i < before.size(); ++i)
    differ = before[i].face_a != after[i].face_a || before[i].segment0 != after[i].segment0;
  ASSERT_TRUE(differ) << "the jiggle should change the contacts";

  GlPositionBuffer shared(gl.fixture.positions, 0, 16);
  GlPositionBuffer a({gl.fixture.positions[0]}, 4, 12);
  GlPositionBuffer b({gl.fixture.positions[1]}, 0, 16);
  for (bool in_place : {true, false}) {
    const std::string what = in_place ? "in place" : "gathered";
    if (in_place) {
      gl.collision.set_positions(shared.sources());
    } else {
      gl.collision.set_positions({a.source(0), b.source(0)});
    }
    for (BroadPhase method : {BroadPhase::kOctree, BroadPhase::kBvh}) {
      shared.write(gl.fixture.positions);
      a.write({gl.fixture.positions[0]});
      b.write({gl.fixture.positions[1]});
      expect_same_pairs(gl.pairs(method), before, what + ", before");
      shared.write(moved.positions);
      a.write({moved.positions[0]});
      b.write({moved.positions[1]});
      expect_same_pairs(gl.pairs(method), after, what + ", after");
    }
  }
}

TEST_F(GlCollisionPositionsTest, ReadPositionsReadsEachSource) {
  GlBackend gl(context(), test::two_crossing_grids());
  const std::vector<std::vector<glm::vec4>>& p = gl.fixture.positions;
  GlPositionBuffer buffer({p[1]}, 8, 12);
  const std::vector<PositionSource> sources = {gl.fixture.host_sources()[0], buffer.source(0)};
  // Before any upload (a detector reads them to build the hierarchies), and after.
  GlCollision fresh(context());
  fresh.set_positions(sources);
  gl.collision.set_positions(sources);
  for (GlCollision* c : {&fresh, &gl.collision}) {
    for (std::uint32_t m = 0; m < 2; ++m) {
      const std::vector<glm::vec3> read = c->read_positions(m);
      ASSERT_EQ(read.size(), p[m].size());
      for (std::size_t i = 0; i < read.size(); ++i)
        ASSERT_EQ(read[i], glm::vec3(p[m][i])) << "mesh " << m << ", vertex " << i;
    }
  }
}

// The GPU check finds the lowest (mesh, vertex) with a NaN or infinite coordinate in the GL
// buffers, skips host arrays (the Detector checks them), and leaves the last pass's results as
// they were.
TEST_F(GlCollisionPositionsTest, FindNonFiniteFindsTheFirstBadVertexAndKeepsTheResults) {
  GlBackend gl(context(), test::three_crossing_grids());
  const std::vector<gpu::FacePair> expected = gl.expected();
  GlPositionBuffer buffer(gl.fixture.positions, 20, 16);
  std::vector<PositionSource> sources = buffer.sources();
  gl.collision.set_positions(sources);
  std::uint32_t mesh = 99;
  std::uint32_t vertex = 99;
  EXPECT_FALSE(gl.collision.find_non_finite(mesh, vertex)) << "NaN padding is not a position";
  gl.collision.detect(BroadPhase::kBvh);  // pending while the checks run
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  buffer.write_coordinate(2, 40, 2, nan);
  buffer.write_coordinate(1, 17, 1, -inf);
  buffer.write_coordinate(1, 9, 0, inf);
  ASSERT_TRUE(gl.collision.find_non_finite(mesh, vertex));
  EXPECT_EQ(mesh, 1u);
  EXPECT_EQ(vertex, 9u);
  const std::vector<glm::vec3> read = gl.collision.read_positions(1);
  EXPECT_TRUE(std::isinf(read[9].x));
  // The pass queued before the checks is whole and unchanged.
  std::vector<gpu::FacePair> pairs;
  gl.collision.download_face_pairs(pairs);
  expect_same_pairs(test::sorted(pairs), expected, "after the check");
  // Mesh 1 from the host: skipped, mesh 2's NaN found.
  sources[1] = gl.fixture.host_sources()[1];
  gl.collision.set_positions(sources);
  ASSERT_TRUE(gl.collision.find_non_finite(mesh, vertex));
  EXPECT_EQ(mesh, 2u);
  EXPECT_EQ(vertex, 40u);
  // Host arrays only: nothing to check on the GPU.
  gl.collision.set_positions(gl.fixture.host_sources());
  EXPECT_FALSE(gl.collision.find_non_finite(mesh, vertex));
  gl.collision.download_face_pairs(pairs);
  expect_same_pairs(test::sorted(pairs), expected, "at the end");
}

// Deleted or reallocated smaller since set_positions: detect() refuses the buffer, naming the
// mesh and the buffer, before running anything (the last results stay); set_positions refuses
// such a buffer at once.
TEST_F(GlCollisionPositionsTest, ABufferDeletedOrShrunkIsRefusedNamingMeshAndBuffer) {
  GlBackend gl(context(), test::two_crossing_grids());
  const std::vector<gpu::FacePair> expected = gl.expected();
  GLuint name = 0;
  glGenBuffers(1, &name);
  glBindBuffer(GL_COPY_WRITE_BUFFER, name);
  const std::vector<glm::vec4>& p1 = gl.fixture.positions[1];
  glBufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(p1.size() * sizeof(glm::vec4)),
               p1.data(), GL_DYNAMIC_DRAW);
  PositionSource s;
  s.kind = PositionSource::Kind::kGl;
  s.gl_buffer = name;
  s.stride_bytes = sizeof(glm::vec4);
  s.vertex_count = static_cast<std::uint32_t>(p1.size());
  std::vector<PositionSource> sources = gl.fixture.host_sources();
  sources[1] = s;
  gl.collision.set_positions(sources);
  expect_same_pairs(gl.pairs(BroadPhase::kBvh), expected, "in a buffer");

  const std::string mesh = "mesh 1 ('grid 7')";
  const std::string buffer = "GL buffer " + std::to_string(name);
  glBindBuffer(GL_COPY_WRITE_BUFFER, name);
  glBufferData(GL_COPY_WRITE_BUFFER, 100, nullptr, GL_DYNAMIC_DRAW);
  for (int round = 0; round < 2; ++round) {
    try {
      gl.collision.detect(BroadPhase::kBvh);
      ADD_FAILURE() << "expected Error";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(mesh), std::string::npos) << what;
      EXPECT_NE(what.find(buffer), std::string::npos) << what;
      EXPECT_NE(what.find(round == 0 ? "holds 100 bytes, fewer than the 1020" : "not a buffer"),
                std::string::npos)
          << what;
    }
    std::vector<gpu::FacePair> pairs;
    gl.collision.download_face_pairs(pairs);
    expect_same_pairs(test::sorted(pairs), expected, "the last results");
    EXPECT_THROW(gl.collision.set_positions(sources), Error);
    glDeleteBuffers(1, &name);
  }
  sources[1].gl_buffer = 0;
  EXPECT_THROW(gl.collision.set_positions(sources), Error);
  sources[1].gl_buffer = name;  // deleted
  sources[1].offset_bytes = 2;
  try {
    gl.collision.set_positions(sources);
    ADD_FAILURE() << "expected Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("offset of 2 bytes"), std::string::npos) << e.what();
  }
}

// Gathered positions are a buffer of the backend's: checked against the buffer limit (a stride
// of 1 KiB makes two meshes of 64 vertices 129 KiB), named with its size and the limit; the same
// positions in one GL buffer are read in place, whatever their size.
TEST_F(GlCollisionPositionsTest, GatheredPositionsOverTheLimitAreRefused) {
  test::CollisionFixture f = test::collision_fixture(test::two_crossing_grids());
  GlCollision gl(context(), {.max_buffer_bytes = 32 * 1024});
  constexpr std::size_t kStrideFloats = 256;
  std::vector<std::vector<float>> sparse(2);
  std::vector<PositionSource> sources;
  for (std::size_t m = 0; m < 2; ++m) {
    sparse[m].assign(f.positions[m].size() * kStrideFloats, 0.0f);
    for (std::size_t i = 0; i < f.positions[m].size(); ++i) {
      for (int k = 0; k < 3; ++k)
        sparse[m][i * kStrideFloats + k] = f.positions[m][i][k];
    }
    PositionSource s = f.host_sources()[m];
    s.host = sparse[m].data();
    s.stride_bytes = kStrideFloats * sizeof(float);
    sources.push_back(s);
  }
  gl.set_positions(sources);
  gl.upload(f.data);
  try {
    gl.detect(BroadPhase::kBvh);
    ADD_FAILURE() << "expected GlError";
  } catch (const GlError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("takes 129048 bytes, more than GlCollisionOptions::max_buffer_bytes "
                        "(32768 bytes)"),
              std::string::npos)
        << what;
  }
  GlPositionBuffer buffer(f.positions, 0, kStrideFloats * sizeof(float));
  gl.set_positions(buffer.sources());
  std::vector<gpu::FacePair> pairs;
  gl.detect(BroadPhase::kBvh);
  gl.download_face_pairs(pairs);
  expect_same_pairs(test::sorted(pairs), test::all_pairs_on_host(f), "in place");
}

}  // namespace
}  // namespace deformcd::gl
