// The contact response's proximity search (Detector::find_proximity) on the impact scene in
// contact: the world runs scenes/impact.json on the CPU for 30 frames (the bodies pressed
// together: the search finds 22,399 pairs), then the search runs again and again on those
// positions, with the reaches and motions a response window gives (each vertex: its body's
// half thickness plus a quarter thickness of play; its velocity over a third of a frame).
// `bench` times whole frames, whose searches vary with the scene's course and share the
// machine's noise; this repeats one search, so two builds can be compared on it. CPU, 1 and 2
// threads (threads:N); between the bodies only (self:0) or each body also against itself
// (self:1, as with `"collision": {"self": true}`).

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "deformcd/detector.h"
#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "deformcd/world.h"
#include "support/collision_fixtures.h"

namespace {

using namespace deformcd;

struct ContactFrame {
  std::vector<CollisionMesh> meshes;
  std::vector<std::vector<glm::vec3>> positions;  // per body, every node
  std::vector<float> reach;                       // per node, bodies in order
  std::vector<glm::vec3> motion;                  // per node, over the window
};

ContactFrame impact_in_contact() {
  const Scene scene = read_scene(std::string(DEFORMCD_SOURCE_DIR) + "/scenes/impact.json");
  constexpr int kFrames = 30;
  const std::vector<BodyInit> bodies = make_scene_bodies(scene, read_tetgen, kFrames);
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  options.cpu_threads = 1;
  options.response = scene.response;
  const StepSettings settings = step_settings(scene.settings);
  World world(bodies, settings, options);
  for (int f = 0; f < kFrames; ++f)
    world.step();
  const float window = settings.dt / 3.0f;  // the impact's searches come about 3 a frame
  ContactFrame frame;
  frame.meshes = test::surface_meshes(bodies);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    frame.positions.push_back(world.positions(b));
    const float thickness = world.contact_thickness(b);
    for (const glm::vec3& v : world.velocities(b)) {
      frame.reach.push_back(0.75f * thickness);
      frame.motion.push_back(v * window);
    }
  }
  return frame;
}

void find_proximity(benchmark::State& state) {
  static const ContactFrame frame = impact_in_contact();
  DetectorOptions options;
  options.backend = BackendKind::kCpu;
  options.threads = static_cast<int>(state.range(0));
  std::vector<CollisionMesh> meshes = frame.meshes;
  for (CollisionMesh& m : meshes)
    m.self_collision = state.range(1) != 0;
  Detector detector(meshes, options);
  for (std::size_t b = 0; b < frame.positions.size(); ++b)
    detector.set_positions(b, std::span<const glm::vec3>(frame.positions[b]));
  detector.prepare();
  std::size_t pairs = detector.find_proximity(frame.reach, frame.motion).size();  // warm-up
  for (auto _ : state) {
    pairs = detector.find_proximity(frame.reach, frame.motion).size();
    benchmark::DoNotOptimize(pairs);
  }
  state.counters["pairs"] = static_cast<double>(pairs);
}

BENCHMARK(find_proximity)
    ->ArgNames({"threads", "self"})
    ->ArgsProduct({{1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
