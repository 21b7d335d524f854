// GL and CPU collision backends on the same positions: the shipped phase scenes replayed on the
// CPU, and at every frame the same positions handed to both collision backends (the CPU one
// reads host arrays, the GL one a GL buffer holding every node as a World's simulation does),
// which must return the same face pairs (segments bit for bit: the GLSL narrow phase mirrors the
// C++), the same flags and the same counts, with every broad phase (the paper's octree every
// third frame); and every broad phase the same pairs as the octree.

#include <algorithm>
#include <filesystem>
#include <memory>
#include <tuple>

#include <gtest/gtest.h>

#include "core/collision/collision_backend.h"
#include "cpu/cpu_collision.h"
#include "cpu/cpu_proximity.h"
#include "cpu/cpu_simulation.h"
#include "deformcd/gl/ssbo.h"
#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "gl/collision_test_backends.h"
#include "gl/gl_test_context.h"
#include "gl/proximity_vertex_lists.h"
#include "gpu/gl/gl_collision.h"
#include "gpu/gl/gl_proximity.h"
#include "support/collision_fixtures.h"

namespace fs = std::filesystem;

namespace deformcd::gl {
namespace {

struct Pass {
  std::vector<gpu::FacePair> pairs;
  std::vector<std::uint32_t> flags;
  gpu::CollisionCounters counters{};
};

auto pair_key(const gpu::FacePair& p) {
  return std::tie(p.face_a, p.face_b, p.coplanar, p.segment0.x, p.segment0.y, p.segment0.z,
                  p.segment1.x, p.segment1.y, p.segment1.z);
}

Pass run(collision::CollisionBackend& collision, BroadPhase method) {
  Pass pass;
  collision.detect(method);
  collision.download_face_pairs(pass.pairs);
  std::sort(
      pass.pairs.begin(), pass.pairs.end(),
      [](const gpu::FacePair& x, const gpu::FacePair& y) { return pair_key(x) < pair_key(y); });
  collision.download_face_flags(pass.flags);
  pass.counters = collision.counters();
  return pass;
}

void expect_same(const Pass& gl, const Pass& cpu, const std::string& where) {
  ASSERT_EQ(gl.pairs.size(), cpu.pairs.size()) << where;
  for (std::size_t i = 0; i < gl.pairs.size(); ++i) {
    ASSERT_TRUE(pair_key(gl.pairs[i]) == pair_key(cpu.pairs[i]))
        << where << ": pair " << i << " is faces " << gl.pairs[i].face_a << "-"
        << gl.pairs[i].face_b << " on GL, " << cpu.pairs[i].face_a << "-" << cpu.pairs[i].face_b
        << " on the CPU (or their segments differ)";
  }
  EXPECT_EQ(std::vector<std::uint32_t>(gl.flags.begin(), gl.flags.begin() + cpu.flags.size()),
            cpu.flags)
      << where;
  EXPECT_EQ(gl.counters.face_pairs, cpu.counters.face_pairs) << where;
  EXPECT_EQ(gl.counters.box_pairs, cpu.counters.box_pairs) << where;
  EXPECT_EQ(gl.counters.colliding_faces, cpu.counters.colliding_faces) << where;
  EXPECT_EQ(gl.counters.candidates, cpu.counters.candidates) << where;
}

// A shipped scene replayed on the CPU over its whole trajectory in `frames` frames; at each
// frame both collision backends test the CPU simulation's positions: the CPU one from host
// arrays (one per mesh), the GL one from a GL buffer of every node (a vec4 each, mesh m's from
// its body's node offset), read in place as a World reads its GL simulation's.
struct SceneReplay {
  SceneReplay(Context& context, const std::string& name, int frames)
      : scene(read_scene(fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / (name + ".json"))),
        bodies(make_scene_bodies(scene, read_tetgen, frames)),
        state(assemble_simulation(bodies)),
        settings(step_settings(scene.settings)),
        fixture(test::collision_fixture(bodies, self_collision(scene))),
        cpu_sim(2),
        cpu_collision(2),
        gl_positions(state.positions.size() * sizeof(glm::vec4)),
        gl_collision(context) {
    cpu_sim.upload(state);
    cpu_collision.set_positions(fixture.host_sources());
    cpu_collision.upload(fixture.data);
    const std::vector<collision::PositionSource> sources =
        test::simulation_sources(gl_positions.name(), state.objects);
    share_positions();
    gl_collision.set_positions(sources);
    gl_collision.upload(fixture.data);
  }

  void step() {
    const float h = settings.dt / static_cast<float>(settings.substeps);
    const sim::SubstepConstants constants{h, settings.gravity,
                                          std::exp(-settings.velocity_damping * h)};
    for (int s = 0; s < settings.substeps; ++s)
      cpu_sim.substep(constants);
    share_positions();
  }

  // The CPU simulation's positions into the host arrays and the GL buffer.
  void share_positions() {
    const std::vector<glm::vec4>& p = cpu_sim.state().positions;
    for (std::size_t b = 0; b < state.objects.size(); ++b) {
      const gpu::ObjectInfo& o = state.objects[b];
      std::copy(p.begin() + o.node_offset, p.begin() + o.node_offset + o.node_count,
                fixture.positions[b].begin());
    }
    gl_positions.upload(p.data(), p.size() * sizeof(glm::vec4));
  }

  // Face count products over the mesh pairs (a mesh with itself: each pair once).
  [[nodiscard]] std::uint64_t all_face_pairs() const {
    std::uint64_t all = 0;
    for (const gpu::BodyPair& p : fixture.data.mesh_pairs) {
      const std::uint64_t a = fixture.data.meshes[p.a].face_count;
      all += p.a == p.b ? a * (a - 1) / 2 : a * fixture.data.meshes[p.b].face_count;
    }
    return all;
  }

  Scene scene;
  std::vector<BodyInit> bodies;
  SimulationState state;
  StepSettings settings;
  test::CollisionFixture fixture;
  cpu::CpuSimulation cpu_sim;
  cpu::CpuCollision cpu_collision;
  BufferObject gl_positions;
  GlCollision gl_collision;
};

class CollisionBackendAgreement : public test_support::GlTest,
                                  public ::testing::WithParamInterface<const char*> {};

TEST_P(CollisionBackendAgreement, GlEqualsCpuOnEveryFrame) {
  constexpr int kFrames = 12;  // the whole trajectory: apart, through each other, apart
  SceneReplay replay(context(), GetParam(), kFrames);
  int frames_in_contact = 0;
  for (int f = 0; f <= kFrames; ++f) {
    if (f > 0) replay.step();
    const std::string frame = ", frame " + std::to_string(f);
    const Pass cpu_octree = run(replay.cpu_collision, BroadPhase::kOctree);
    frames_in_contact += cpu_octree.pairs.empty() ? 0 : 1;
    // The paper's octree on GL launches N' x M' invocations (12 s a frame here on llvmpipe) and
    // the all-pairs baseline every face pair: both mid-contact only. GL's other methods are
    // compared with the CPU's octree on every frame below, apart and in contact, and the CPU's
    // methods with each other on every frame by test_world's CollisionOnScenes.
    const bool mid_contact = f == kFrames / 2;
    if (mid_contact) {
      EXPECT_FALSE(cpu_octree.pairs.empty()) << GetParam() << frame;
    }
    for (BroadPhase method : {BroadPhase::kOctree, BroadPhase::kOctreeCompact, BroadPhase::kBvh}) {
      if (method == BroadPhase::kOctree && !mid_contact) continue;
      const std::string where =
          std::string(GetParam()) + " " + std::string(broadphase_name(method)) + frame;
      const Pass cpu =
          method == BroadPhase::kOctree ? cpu_octree : run(replay.cpu_collision, method);
      const Pass gl = run(replay.gl_collision, method);
      expect_same(gl, cpu, where);
      // And the octree's contacts (the counts of what was culled differ).
      Pass octree_pairs = cpu_octree;
      octree_pairs.counters = cpu.counters;
      expect_same(gl, octree_pairs, where + " against the octree");
    }
    // The all-pairs baseline on GL; the CPU tests compare it with the octree on every frame.
    if (mid_contact) {
      const Pass gl_brute = run(replay.gl_collision, BroadPhase::kBrute);
      Pass expected = cpu_octree;
      expected.counters.box_pairs = 0;
      expected.counters.candidates = gl_brute.counters.candidates;
      expect_same(gl_brute, expected, std::string(GetParam()) + " brute" + frame);
      EXPECT_EQ(gl_brute.counters.candidates, replay.all_face_pairs()) << "brute" << frame;
    }
  }
  EXPECT_GE(frames_in_contact, 2);
}

INSTANTIATE_TEST_SUITE_P(ShippedScenes, CollisionBackendAgreement,
                         ::testing::Values("phase1", "phase2"));

class CollisionBackendSelf : public test_support::GlTest {};

// The plate of scenes/fold.json folding into itself (self-collision: one mesh pair (0, 0), faces
// sharing an edge skipped, faces sharing a node tested beyond it): every broad phase on GL
// returns the CPU's pairs, segments bit for bit, and the same counts, the all-pairs baseline
// included, at rest, while it bends (frame 3) and through the fold (30-40: 228-446 pairs). The
// baseline and the paper's octree on GL (seconds a frame on llvmpipe) while it bends and
// mid-fold (frame 35); on the CPU every method on every frame checked.
TEST_F(CollisionBackendSelf, GlEqualsCpuOnTheFoldingPlate) {
  constexpr int kFrames = 40;
  SceneReplay replay(context(), "fold", 120);
  ASSERT_EQ(replay.fixture.data.mesh_pairs.size(), 1u);
  ASSERT_EQ(replay.fixture.data.mesh_pairs[0].a, replay.fixture.data.mesh_pairs[0].b);
  int frames_in_contact = 0;
  for (int f = 0; f <= kFrames; ++f) {
    if (f > 0) replay.step();
    if (f != 0 && f != 3 && f != 30 && f != 35 && f != kFrames) continue;
    const std::string frame = ", frame " + std::to_string(f);
    const Pass cpu_brute = run(replay.cpu_collision, BroadPhase::kBrute);
    frames_in_contact += cpu_brute.pairs.empty() ? 0 : 1;
    for (BroadPhase method :
         {BroadPhase::kBrute, BroadPhase::kOctree, BroadPhase::kOctreeCompact, BroadPhase::kBvh}) {
      const std::string where = "fold " + std::string(broadphase_name(method)) + frame;
      const Pass cpu = method == BroadPhase::kBrute ? cpu_brute : run(replay.cpu_collision, method);
      const bool costly = method == BroadPhase::kBrute || method == BroadPhase::kOctree;
      if (!costly || f == 3 || f == 35) expect_same(run(replay.gl_collision, method), cpu, where);
      Pass brute_pairs = cpu_brute;
      brute_pairs.counters = cpu.counters;
      expect_same(cpu, brute_pairs, where + " against brute");
    }
    // The baseline counts each pair of the mesh's faces once.
    EXPECT_EQ(cpu_brute.counters.candidates, replay.all_face_pairs()) << frame;
  }
  EXPECT_GE(frames_in_contact, 3);
}

class ProximityAgreement : public test_support::GlTest {};

// The GL backend's proximity phase (GlCollision::find_proximity) over its trees, on the
// simulation's positions read in place, gives the host search's list over the same trees
// exactly on phase 1's models (thousands of faces) before, in and after contact, each vertex
// moving along its velocity over a frame, with a contact response's reaches (a few mm) and
// longer ones, varying from vertex to vertex.
TEST_F(ProximityAgreement, GlEqualsCpuThroughPhase1) {
  constexpr int kFrames = 12;
  SceneReplay replay(context(), "phase1", kFrames);
  test::HostProximity cpu(replay.fixture.data, replay.fixture.vertices());
  const std::vector<std::uint32_t> pairs = collision::searched_mesh_pairs(replay.fixture.data, {});
  std::size_t longest = 0;
  std::size_t compared = 0;
  for (int f = 0; f <= kFrames; ++f) {
    if (f > 0) replay.step();
    if (f % 3 != 0) continue;
    // Each node's motion over the next frame: its velocity x dt.
    std::vector<glm::vec3> motion;
    for (const glm::vec4& v : replay.cpu_sim.state().velocities)
      motion.push_back(glm::vec3(v) * replay.settings.dt);
    for (const std::vector<float>& reach :
         {std::vector<float>{0.002f, 0.003f}, std::vector<float>{0.02f, 0.01f}}) {
      for (const bool moving : {false, true}) {
        test::VertexLists lists =
            test::vertex_lists(replay.fixture.data, reach, {}, 0.0f, static_cast<std::uint32_t>(f));
        if (moving) {
          lists.motion = motion;
          lists.repoint();
        }
        const std::vector<collision::ProximityCandidate> expected = cpu.search.find(
            replay.fixture.vertices(), lists.cpu_motion(), lists.cpu_reach(), pairs);
        std::vector<float> distances;
        const std::vector<collision::ProximityCandidate> found = replay.gl_collision.find_proximity(
            lists.query(replay.fixture.vertices(), pairs), distances);
        const std::string where = "frame " + std::to_string(f) + ", reach " +
                                  std::to_string(reach[0]) + (moving ? ", moving" : "");
        EXPECT_EQ(found.size(), expected.size()) << where;
        EXPECT_TRUE(found == expected) << where;
        longest = std::max(longest, expected.size());
        compared += expected.size();
      }
    }
  }
  EXPECT_GT(longest, 100u) << "the models should come within reach";
  RecordProperty("candidates_compared", std::to_string(compared));
}

class CollisionBackendManyBodies : public test_support::GlTest {};

// Sixteen bodies crossing in two lanes (120 mesh pairs, most of them apart at any time, culled
// by their root boxes on the GPU): the broad phases beyond the paper agree with the CPU's, and
// with each other. (The paper's octree and the baseline would take minutes here on llvmpipe.)
TEST_F(CollisionBackendManyBodies, GlEqualsCpuWithSixteenBodies) {
  constexpr int kFrames = 8;
  SceneReplay replay(context(), "crossing16", kFrames);
  ASSERT_EQ(replay.fixture.data.mesh_pairs.size(), 120u);
  int frames_in_contact = 0;
  for (int f = 0; f <= kFrames; ++f) {
    if (f > 0) replay.step();
    const std::string frame = ", frame " + std::to_string(f);
    const Pass cpu_bvh = run(replay.cpu_collision, BroadPhase::kBvh);
    frames_in_contact += cpu_bvh.pairs.empty() ? 0 : 1;
    expect_same(run(replay.gl_collision, BroadPhase::kBvh), cpu_bvh, "crossing16 bvh" + frame);
    const Pass cpu_compact = run(replay.cpu_collision, BroadPhase::kOctreeCompact);
    const Pass gl_compact = run(replay.gl_collision, BroadPhase::kOctreeCompact);
    expect_same(gl_compact, cpu_compact, "crossing16 octree-compact" + frame);
    Pass bvh_pairs = cpu_bvh;
    bvh_pairs.counters = cpu_compact.counters;
    expect_same(gl_compact, bvh_pairs, "crossing16 octree-compact against bvh" + frame);
  }
  EXPECT_GE(frames_in_contact, 2);
}

}  // namespace
}  // namespace deformcd::gl
