// The public Detector, on every backend (parameterised: cpu, gl), as a caller uses it: its own
// triangle meshes (closed and open), positions in its own arrays moved in place between passes.
// Every broad phase returns exactly the pairs of an independent all-pairs test; face ids are
// the caller's; bad input leaves the detector as it was.

#include "deformcd/detector.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "core/collision/face_pair_intersection.h"
#include "core/collision/vertex_positions.h"
#include "deformcd/error.h"
#include "detector/detector_scenes.h"
#include "support/contact_compare.h"

#ifdef DEFORMCD_TEST_GL
#include <epoxy/gl.h>

#include "gl/gl_test_context.h"
#endif

namespace deformcd {
namespace {

using test::CallerMesh;

const std::vector<BroadPhase> kMethods = {BroadPhase::kBrute, BroadPhase::kOctree,
                                          BroadPhase::kOctreeCompact, BroadPhase::kBvh};

// The meshes' positions, as the detector reads them (packed vec3 arrays).
std::vector<collision::MeshVertices> views_of(const std::vector<CallerMesh>& meshes) {
  std::vector<collision::MeshVertices> views;
  for (const CallerMesh& m : meshes)
    views.push_back({&m.positions[0].x, 3u});
  return views;
}

// Every listed pair of meshes, every pair of their triangles, through the narrow phase alone:
// what every broad phase must return. Pairs of one mesh keep face_a < face_b.
std::vector<std::array<std::uint32_t, 4>> all_pairs_oracle(const std::vector<CallerMesh>& meshes,
                                                           const std::vector<MeshPair>& pairs) {
  const std::vector<collision::MeshVertices> views = views_of(meshes);
  std::vector<std::array<std::uint32_t, 4>> found;
  for (const MeshPair& p : pairs) {
    const CollisionMesh& a = meshes[p.a].mesh;
    const CollisionMesh& b = meshes[p.b].mesh;
    for (std::uint32_t i = 0; i < a.triangles.size(); ++i) {
      for (std::uint32_t j = p.a == p.b ? i + 1 : 0; j < b.triangles.size(); ++j) {
        const Triangle& ta = a.triangles[i];
        const Triangle& tb = b.triangles[j];
        const gpu::Face fa{ta[0], ta[1], ta[2], p.a};
        const gpu::Face fb{tb[0], tb[1], tb[2], p.b};
        if (collision::face_pair_intersect(fa, fb, views.data()).intersect) {
          found.push_back({p.a, i, p.b, j});
        }
      }
    }
  }
  std::sort(found.begin(), found.end());
  return found;
}

std::vector<std::array<std::uint32_t, 4>> keys(const std::vector<Contact>& contacts) {
  std::vector<std::array<std::uint32_t, 4>> k;
  for (const Contact& c : contacts)
    k.push_back({c.a.body, c.a.face, c.b.body, c.b.face});
  return k;
}

// A sphere, a second sphere crossing it, and an open cloth draped through both.
std::vector<CallerMesh> crossing_meshes() {
  return {test::sphere_mesh(3, 0.5f, {0.0f, 0.0f, 0.0f}),
          test::sphere_mesh(2, 0.4f, {0.55f, 0.21f, 0.13f}),
          test::cloth_mesh(24, 2.0f, {0.2f, 0.05f, 0.03f}, 0.15f)};
}

std::vector<CollisionMesh> meshes_of(const std::vector<CallerMesh>& m) {
  std::vector<CollisionMesh> out;
  for (const CallerMesh& c : m)
    out.push_back(c.mesh);
  return out;
}

class DetectorTest : public ::testing::TestWithParam<BackendKind> {
 protected:
  void SetUp() override {
#ifdef DEFORMCD_TEST_GL
    if (GetParam() == BackendKind::kGl) {
      gl::test_support::ContextAttempt& shared = gl::test_support::shared_context();
      if (!shared.context) DEFORMCD_GL_UNAVAILABLE(shared.why_not);
      shared.context->make_current();
      context_ = shared.context.get();
    }
#endif
  }

  // A detector on the backend under test over `meshes`, reading their positions in place.
  Detector make(std::vector<CallerMesh>& meshes, DetectorOptions options = {}) {
    options.backend = GetParam();
    options.gl_context = context_;
    Detector d(meshes_of(meshes), options);
    for (std::size_t m = 0; m < meshes.size(); ++m)
      d.set_positions(m, std::span<const glm::vec3>(meshes[m].positions));
    return d;
  }

  gl::Context* context_ = nullptr;
};

std::string name_of(const ::testing::TestParamInfo<BackendKind>& info) {
  return info.param == BackendKind::kGl ? "gl" : "cpu";
}

TEST_P(DetectorTest, EveryBroadPhaseReturnsExactlyTheAllPairsOracle) {
  std::vector<CallerMesh> meshes = crossing_meshes();
  Detector d = make(meshes);
  EXPECT_EQ(d.backend_name(), GetParam() == BackendKind::kGl ? "gl" : "cpu");
  const std::vector<MeshPair> all = {{0, 1}, {0, 2}, {1, 2}};
  for (int frame = 0; frame < 3; ++frame) {
    // The caller moves its meshes in place; the detector refits (or rebuilds) on its own.
    for (glm::vec3& p : meshes[1].positions)
      p += glm::vec3(-0.07f, 0.015f, 0.01f);
    for (glm::vec3& p : meshes[2].positions)
      p.y += 0.03f * std::sin(4.0f * p.x + static_cast<float>(frame));
    const auto oracle = all_pairs_oracle(meshes, all);
    ASSERT_GT(oracle.size(), 50u) << "frame " << frame;
    std::optional<std::vector<Contact>> reference;
    for (BroadPhase method : kMethods) {
      d.set_broadphase(method);
      d.detect();
      const std::vector<Contact> contacts = d.contacts();
      EXPECT_EQ(keys(contacts), oracle) << broadphase_name(method) << ", frame " << frame;
      if (!reference) {
        reference = contacts;
      } else {
        EXPECT_EQ(test::contacts_difference(contacts, *reference), "")
            << broadphase_name(method) << ", frame " << frame;
      }
      EXPECT_EQ(d.counts().contacts, contacts.size());
    }
  }
}

TEST_P(DetectorTest, FaceIdsAndNodesAreTheCallersAndFlagsMatch) {
  std::vector<CallerMesh> meshes = crossing_meshes();
  // Shuffle the triangles of the cloth: contacts must name them by their new index.
  std::vector<CallerMesh> shuffled = meshes;
  std::vector<std::uint32_t> order(meshes[2].mesh.triangles.size());
  std::iota(order.begin(), order.end(), 0u);
  std::reverse(order.begin(), order.end());
  std::rotate(order.begin(), order.begin() + 37, order.end());
  for (std::size_t i = 0; i < order.size(); ++i)
    shuffled[2].mesh.triangles[i] = meshes[2].mesh.triangles[order[i]];
  Detector d = make(meshes);
  Detector s = make(shuffled);
  d.detect();
  s.detect();
  const std::vector<Contact> plain = d.contacts();
  const std::vector<Contact> moved = s.contacts();
  ASSERT_EQ(plain.size(), moved.size());
  std::vector<std::array<std::uint32_t, 4>> mapped;
  for (const Contact& c : moved) {
    const std::uint32_t fa = c.a.body == 2 ? order[c.a.face] : c.a.face;
    const std::uint32_t fb = c.b.body == 2 ? order[c.b.face] : c.b.face;
    mapped.push_back({c.a.body, fa, c.b.body, fb});
    // The nodes are the caller's triangle's vertices.
    EXPECT_EQ(c.a.nodes, shuffled[c.a.body].mesh.triangles[c.a.face]);
    EXPECT_EQ(c.b.nodes, shuffled[c.b.body].mesh.triangles[c.b.face]);
  }
  std::sort(mapped.begin(), mapped.end());
  EXPECT_EQ(mapped, keys(plain));

  const std::vector<std::uint32_t> flags = d.face_flags();
  ASSERT_EQ(flags.size(), d.face_count());
  std::vector<std::uint32_t> expected(d.face_count(), 0u);
  for (const Contact& c : plain) {
    expected[d.face_offset(c.a.body) + c.a.face] = 1u;
    expected[d.face_offset(c.b.body) + c.b.face] = 1u;
  }
  std::vector<std::uint32_t> nonzero(flags.size());
  std::transform(flags.begin(), flags.end(), nonzero.begin(),
                 [](std::uint32_t f) { return f != 0u ? 1u : 0u; });
  EXPECT_EQ(nonzero, expected);
}

TEST_P(DetectorTest, OpenClothFoldedOntoItselfHasSelfContactsOnlyWhenAsked) {
  std::vector<CallerMesh> meshes = {test::cloth_mesh(20, 1.0f, {0.0f, 0.0f, 0.0f}, 0.05f)};
  test::fold_cloth(meshes[0], 0.0f, 0.25f);
  Detector off = make(meshes);
  off.detect();
  EXPECT_TRUE(off.contacts().empty());
  meshes[0].mesh.self_collision = true;
  Detector on = make(meshes);
  const auto oracle = all_pairs_oracle(meshes, {{0, 0}});
  ASSERT_GT(oracle.size(), 10u);
  for (BroadPhase method : kMethods) {
    on.set_broadphase(method);
    on.detect();
    EXPECT_EQ(keys(on.contacts()), oracle) << broadphase_name(method);
  }
}

TEST_P(DetectorTest, MeshPairListLeavesOutGluedMeshes) {
  std::vector<CallerMesh> meshes = crossing_meshes();
  DetectorOptions options;
  options.mesh_pairs = std::vector<MeshPair>{{2, 0}, {1, 2}};  // not (0, 1): glued
  Detector d = make(meshes, options);
  const auto oracle = all_pairs_oracle(meshes, {{0, 2}, {1, 2}});
  for (BroadPhase method : kMethods) {
    d.set_broadphase(method);
    d.detect();
    EXPECT_EQ(keys(d.contacts()), oracle) << broadphase_name(method);
  }
}

TEST_P(DetectorTest, StridedPositionsGiveBitIdenticalContacts) {
  std::vector<CallerMesh> meshes = crossing_meshes();
  Detector packed = make(meshes);
  packed.detect();
  // The same positions as vec4 with something else in w, and with 8 bytes of padding.
  std::vector<std::vector<float>> vec4(meshes.size()), padded(meshes.size());
  DetectorOptions options;
  options.backend = GetParam();
  options.gl_context = context_;
  Detector wide(meshes_of(meshes), options);
  Detector gaps(meshes_of(meshes), options);
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    for (const glm::vec3& p : meshes[m].positions) {
      vec4[m].insert(vec4[m].end(), {p.x, p.y, p.z, 42.0f});
      padded[m].insert(padded[m].end(), {p.x, p.y, p.z, -1.0f, 7.0f});
    }
    wide.set_positions(m, HostPositions{vec4[m].data(), 4 * sizeof(float)});
    gaps.set_positions(m, HostPositions{padded[m].data(), 5 * sizeof(float)});
  }
  wide.detect();
  gaps.detect();
  ASSERT_FALSE(packed.contacts().empty());
  EXPECT_EQ(test::contacts_difference(wide.contacts(), packed.contacts()), "");
  EXPECT_EQ(test::contacts_difference(gaps.contacts(), packed.contacts()), "");
}

TEST_P(DetectorTest, MovedPositionsNeedNoCallToRefitOrRebuild) {
  // FCL's stale-box trap (its issue #577) must not exist: moving the arrays is all it takes.
  std::vector<CallerMesh> meshes = crossing_meshes();
  Detector d = make(meshes);
  d.detect();
  const std::vector<Contact> before = d.contacts();
  // Far apart, then crumpled back into each other: refits and rebuilds happen inside.
  for (glm::vec3& p : meshes[1].positions)
    p += glm::vec3(5.0f, 0.0f, 0.0f);
  d.detect();
  for (const Contact& c : d.contacts())
    EXPECT_TRUE(c.a.body != 1 && c.b.body != 1);
  Detector apart = make(meshes);
  apart.detect();
  EXPECT_EQ(test::contacts_difference(d.contacts(), apart.contacts()), "");
  for (glm::vec3& p : meshes[1].positions)
    p = glm::vec3(-p.y, p.x - 5.0f, 0.5f * p.z) * 1.1f;
  d.detect();
  Detector fresh = make(meshes);
  fresh.detect();
  EXPECT_NE(keys(d.contacts()), keys(before));
  EXPECT_EQ(test::contacts_difference(d.contacts(), fresh.contacts()), "");
}

TEST_P(DetectorTest, DegenerateTrianglesIntersectNothing) {
  CallerMesh slab = test::cloth_mesh(2, 1.0f, {0.0f, 0.0f, 0.0f}, 0.0f);
  // A needle through the slab: a triangle with a repeated vertex, one with collinear corners,
  // and a proper one as the control.
  CallerMesh needles;
  needles.positions = {{0.1f, -1.0f, 0.1f},  {0.1f, 1.0f, 0.1f},  {0.1f, 0.0f, 0.1f},
                       {-0.2f, -1.0f, 0.0f}, {-0.2f, 1.0f, 0.0f}, {-0.1f, 1.0f, 0.0f}};
  needles.mesh.vertex_count = 6;
  needles.mesh.triangles = {{0, 1, 1}, {0, 1, 2}, {3, 4, 5}};
  std::vector<CallerMesh> meshes = {slab, needles};
  Detector d = make(meshes);
  for (BroadPhase method : kMethods) {
    d.set_broadphase(method);
    d.detect();
    const std::vector<Contact> c = d.contacts();
    ASSERT_FALSE(c.empty()) << broadphase_name(method);
    for (const Contact& x : c)
      EXPECT_EQ(x.b.face, 2u) << broadphase_name(method);
  }
}

TEST_P(DetectorTest, BadInputIsNamedAndLeavesTheLastResults) {
  std::vector<CallerMesh> meshes = crossing_meshes();
  {
    std::vector<CollisionMesh> bad = meshes_of(meshes);
    bad[1].triangles[5] = {0, 1, bad[1].vertex_count};
    DetectorOptions options{.backend = GetParam(), .gl_context = context_};
    try {
      Detector d(bad, options);
      FAIL() << "no error";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("mesh 1 ('sphere')"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("triangle 5"), std::string::npos) << e.what();
    }
    options.mesh_pairs = std::vector<MeshPair>{{0, 3}};
    EXPECT_THROW(Detector(meshes_of(meshes), options), InputError);
  }
  DetectorOptions options{.backend = GetParam(), .gl_context = context_};
  Detector unset(meshes_of(meshes), options);
  unset.set_positions(0, std::span<const glm::vec3>(meshes[0].positions));
  try {
    unset.detect();
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mesh 1 ('sphere'): has no positions"), std::string::npos)
        << e.what();
  }
}

TEST_P(DetectorTest, NonFinitePositionsAreNamedAndTheLastResultsStay) {
  std::vector<CallerMesh> meshes = crossing_meshes();
  Detector d = make(meshes);
  d.detect();
  const std::vector<Contact> good = d.contacts();
  ASSERT_FALSE(good.empty());
  meshes[1].positions[17].y = std::numeric_limits<float>::quiet_NaN();
  try {
    d.detect();
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mesh 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("vertex 17"), std::string::npos) << e.what();
  }
  EXPECT_EQ(test::contacts_difference(d.contacts(), good), "");
  meshes[1].positions[17].y = std::numeric_limits<float>::infinity();
  EXPECT_THROW(d.detect(), InputError);
  EXPECT_EQ(test::contacts_difference(d.contacts(), good), "");
}

TEST_P(DetectorTest, WrongPositionCountsAndMeshesAreErrors) {
  std::vector<CallerMesh> meshes = crossing_meshes();
  Detector d = make(meshes);
  std::vector<glm::vec3> short_array(meshes[0].positions.begin(), meshes[0].positions.end() - 1);
  EXPECT_THROW(d.set_positions(0, std::span<const glm::vec3>(short_array)), InputError);
  EXPECT_THROW(d.set_positions(7, std::span<const glm::vec3>(meshes[0].positions)), InputError);
  EXPECT_THROW(d.set_positions(0, HostPositions{nullptr, 12}), InputError);
  EXPECT_THROW(d.set_positions(0, HostPositions{&meshes[0].positions[0].x, 8}), InputError);
  d.detect();  // unchanged: still the caller's arrays
  EXPECT_FALSE(d.contacts().empty());
}

#ifdef DEFORMCD_TEST_GL
// A caller's GL buffer (a VBO its renderer draws from): two meshes in one buffer at byte
// offsets, packed xyz (12-byte stride), read in place by the shaders; and the third mesh from a
// buffer of its own (copied on the GPU). Bit for bit what host positions give.
// GL buffers need the GL backend: this suite runs on it alone.
class DetectorGlTest : public DetectorTest {};

TEST_P(DetectorGlTest, PositionsInTheCallersGlBufferEqualHostPositions) {
  std::vector<CallerMesh> meshes = crossing_meshes();
  Detector host = make(meshes);
  host.detect();
  const std::vector<Contact> expected = host.contacts();
  ASSERT_FALSE(expected.empty());

  const std::size_t head = 64;  // bytes before the first mesh: another attribute, say
  std::vector<char> bytes(head);
  std::vector<std::size_t> offsets;
  for (std::size_t m = 0; m < 2; ++m) {
    offsets.push_back(bytes.size());
    const char* p = reinterpret_cast<const char*>(meshes[m].positions.data());
    bytes.insert(bytes.end(), p, p + meshes[m].positions.size() * sizeof(glm::vec3));
  }
  GLuint buffers[2] = {0, 0};
  glGenBuffers(2, buffers);
  glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(bytes.size()), bytes.data(),
               GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, buffers[1]);
  glBufferData(GL_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(meshes[2].positions.size() * sizeof(glm::vec3)),
               meshes[2].positions.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  {
    Detector shared(meshes_of(meshes), {.backend = BackendKind::kGl, .gl_context = context_});
    shared.set_positions(0, GlPositions{buffers[0], offsets[0], sizeof(glm::vec3)});
    shared.set_positions(1, GlPositions{buffers[0], offsets[1], sizeof(glm::vec3)});
    shared.set_positions(2, GlPositions{buffers[1], 0, sizeof(glm::vec3)});
    for (BroadPhase method : kMethods) {
      shared.set_broadphase(method);
      shared.detect();
      EXPECT_EQ(test::contacts_difference(shared.contacts(), expected), "")
          << broadphase_name(method);
    }
    // A buffer too small for its mesh, and a NaN in a buffer, are named.
    EXPECT_THROW(shared.set_positions(2, GlPositions{buffers[1], 64, sizeof(glm::vec3)}),
                 InputError);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
    glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(offsets[1] + 9 * sizeof(glm::vec3)),
                    sizeof(float), &nan);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    try {
      shared.detect();
      FAIL() << "no error";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("mesh 1"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("vertex 9"), std::string::npos) << e.what();
    }
    EXPECT_EQ(test::contacts_difference(shared.contacts(), expected), "");
  }
  glDeleteBuffers(2, buffers);
}
#endif

#ifdef DEFORMCD_TEST_GL
INSTANTIATE_TEST_SUITE_P(Backends, DetectorTest,
                         ::testing::Values(BackendKind::kCpu, BackendKind::kGl), name_of);
INSTANTIATE_TEST_SUITE_P(Gl, DetectorGlTest, ::testing::Values(BackendKind::kGl), name_of);
#else
INSTANTIATE_TEST_SUITE_P(Backends, DetectorTest, ::testing::Values(BackendKind::kCpu), name_of);
#endif

TEST(DetectorCpu, ResultsDoNotDependOnTheThreadCount) {
  std::vector<CallerMesh> meshes = crossing_meshes();
  std::optional<std::vector<Contact>> reference;
  for (int threads : {1, 2, 3, 8}) {
    for (BroadPhase method : kMethods) {
      Detector d(meshes_of(meshes),
                 {.backend = BackendKind::kCpu, .broadphase = method, .threads = threads});
      for (std::size_t m = 0; m < meshes.size(); ++m)
        d.set_positions(m, std::span<const glm::vec3>(meshes[m].positions));
      d.detect();
      if (!reference) reference = d.contacts();
      EXPECT_EQ(test::contacts_difference(d.contacts(), *reference), "")
          << threads << " threads, " << broadphase_name(method);
    }
  }
}

TEST(DetectorCpu, GlPositionsNeedTheGlBackend) {
  std::vector<CallerMesh> meshes = crossing_meshes();
  Detector d(meshes_of(meshes), {.backend = BackendKind::kCpu});
  EXPECT_THROW(d.set_positions(0, GlPositions{1, 0, 16}), Error);
}

}  // namespace
}  // namespace deformcd
