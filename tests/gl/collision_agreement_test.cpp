// GL and CPU collision backends on the same positions: the shipped phase scenes replayed on the
// CPU, and at every frame the same world state handed to both collision backends, which must
// return the same face pairs (segments bit for bit: the GLSL narrow phase mirrors the C++) and
// the same flags, with both broad phases.

#include <algorithm>
#include <filesystem>
#include <tuple>

#include <gtest/gtest.h>

#include "cpu/cpu_collision.h"
#include "cpu/cpu_simulation.h"
#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "gl_test_context.h"
#include "gpu/gl/gl_collision.h"
#include "gpu/gl/gl_simulation.h"

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

template <class Collision>
Pass run(Collision& collision, BroadPhase method) {
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
}

class CollisionBackendAgreement : public test_support::GlTest,
                                  public ::testing::WithParamInterface<const char*> {};

TEST_P(CollisionBackendAgreement, GlEqualsCpuOnEveryFrame) {
  constexpr int kFrames = 12;  // the whole trajectory: apart, through each other, apart
  const Scene scene =
      read_scene(fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / (std::string(GetParam()) + ".json"));
  WorldState state = assemble_world(make_scene_bodies(scene, read_tetgen, kFrames));
  const StepSettings settings = step_settings(scene.settings);
  const float h = settings.dt / static_cast<float>(settings.substeps);
  const sim::SubstepConstants constants{h, settings.gravity,
                                        std::exp(-settings.velocity_damping * h)};

  cpu::CpuSimulation cpu_sim;
  cpu_sim.upload(state);
  cpu::CpuCollision cpu_collision(cpu_sim);
  cpu_collision.upload(state);
  GlSimulation gl_sim(context());
  GlCollision gl_collision(context(), gl_sim);
  gl_collision.upload(state);

  int frames_in_contact = 0;
  for (int f = 0; f <= kFrames; ++f) {
    if (f > 0) {
      for (int s = 0; s < settings.substeps; ++s)
        cpu_sim.substep(constants);
    }
    // The GL side gets the CPU's positions, so that both test the same floats.
    state.positions = cpu_sim.state().positions;
    gl_sim.upload(state);
    const Pass cpu_octree = run(cpu_collision, BroadPhase::kOctree);
    const Pass gl_octree = run(gl_collision, BroadPhase::kOctree);
    expect_same(gl_octree, cpu_octree,
                std::string(GetParam()) + " octree, frame " + std::to_string(f));
    frames_in_contact += cpu_octree.pairs.empty() ? 0 : 1;
    // The all-pairs baseline on GL: at the start and mid-contact (time on a software
    // rasterizer); the CPU tests compare it with the octree on every frame.
    if (f == 0 || f == kFrames / 2) {
      const Pass gl_brute = run(gl_collision, BroadPhase::kBrute);
      Pass expected = cpu_octree;
      expected.counters.box_pairs = 0;
      expect_same(gl_brute, expected,
                  std::string(GetParam()) + " brute, frame " + std::to_string(f));
    }
  }
  EXPECT_GE(frames_in_contact, 2);
}

INSTANTIATE_TEST_SUITE_P(ShippedScenes, CollisionBackendAgreement,
                         ::testing::Values("phase1", "phase2"));

}  // namespace
}  // namespace deformcd::gl
