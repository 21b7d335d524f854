// deformcd against the libraries a user would pick instead, on identical frames: the contact
// frames of the shipped phase scenes and, when its models have been generated
// (scripts/make_models.sh --fine), of scenes/scaling/phase1_50k (about 50k faces per body);
// positions replayed on the CPU backend, each contestant finding every intersecting
// surface-triangle pair between the two bodies.
//   deformcd-<method>: a public deformcd::Detector (CPU backend) over the two meshes, reading the
//        caller's xyz arrays in place: each frame's positions are written into them (untimed, as
//        the caller's simulation would), then detect() and contacts() are timed (box update or
//        refit included). "/threads:1" runs it on one thread, "/threads:all" on every core.
//   fcl: FCL 0.7 BVHModel<AABB> per body, refitted each frame (beginUpdateModel /
//        updateSubModel / endUpdateModel), collide() with exhaustive contacts.
//   cgal: CGAL box_intersection_d over the faces' boxes, then do_intersect on Triangle_3 (Epick).
// One iteration runs every kept contact frame once; the time reported is per frame (wall clock,
// the iteration's time divided by the frames), "contacts" is the number found over the frames:
// peers must match deformcd's up to the float test's uncertain zone ("replay_contacts": what
// deformcd's bvh found while replaying the scene).

#include <benchmark/benchmark.h>

#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "contact_frames.h"
#include "deformcd/detector.h"
#include "deformcd/error.h"
#include "deformcd/scene.h"
#include "peer_contestants.h"

namespace {

using namespace deformcd;

constexpr int kSceneFrames = 48;  // the whole trajectory
constexpr int kKeptFrames = 6;    // contact frames measured

const bench::ContactFrames& frames_of(const std::string& scene) {
  static std::map<std::string, bench::ContactFrames> cache;
  auto it = cache.find(scene);
  if (it == cache.end()) {
    it = cache.emplace(scene, bench::contact_frames(scene, kSceneFrames, kKeptFrames)).first;
  }
  return it->second;
}

void report(benchmark::State& state, const bench::ContactFrames& f, std::size_t found) {
  state.counters["contacts"] =
      benchmark::Counter(static_cast<double>(found), benchmark::Counter::kAvgIterations);
  state.counters["replay_contacts"] = 0.0;
  for (std::size_t c : f.contacts)
    state.counters["replay_contacts"] += static_cast<double>(c);
  state.counters["frames"] = static_cast<double>(f.positions.size());
  state.counters["faces"] = static_cast<double>(f.face_count());
  // Wall time per frame (one iteration covers every frame): frames per second, inverted.
  state.counters["per_frame"] = benchmark::Counter(
      static_cast<double>(f.positions.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void deformcd_method(benchmark::State& state, const std::string& scene, BroadPhase method,
                     int threads) {
  const bench::ContactFrames& f = frames_of(scene);
  Detector detector(f.meshes,
                    {.backend = BackendKind::kCpu, .broadphase = method, .threads = threads});
  // The caller's arrays, read in place by every detect().
  bench::FramePositions current = f.positions.front();
  for (std::size_t m = 0; m < current.size(); ++m)
    detector.set_positions(m, std::span<const glm::vec3>(current[m]));
  detector.prepare();
  std::size_t found = 0;
  for (auto _ : state) {
    for (const bench::FramePositions& positions : f.positions) {
      state.PauseTiming();
      for (std::size_t m = 0; m < current.size(); ++m)
        std::copy(positions[m].begin(), positions[m].end(), current[m].begin());
      state.ResumeTiming();
      detector.detect();
      found += detector.counts().contacts;
    }
  }
  report(state, f, found);
}

void peer(benchmark::State& state, const std::string& scene, const std::string& name) {
  const bench::ContactFrames& f = frames_of(scene);
  std::unique_ptr<bench::PeerContestant> contestant =
      bench::make_peer(name, f.meshes, f.positions.front());
  std::size_t found = 0;
  for (auto _ : state) {
    for (const bench::FramePositions& positions : f.positions)
      found += contestant->detect(positions);
  }
  report(state, f, found);
}

// A scene of the comparison and the deformcd methods run on it.
struct ComparedScene {
  std::string name;  // scenes/NAME.json
  std::vector<BroadPhase> methods;
  bool generated_models;  // its models are made by scripts/make_models.sh --fine, not shipped
};

// False (with a message) when a fine scene's models have not been generated: the shipped
// comparison still runs. The scene reader's error names the missing model.
bool available(const ComparedScene& scene) {
  if (!scene.generated_models) return true;
  try {
    (void)read_scene(std::string(DEFORMCD_SOURCE_DIR) + "/scenes/" + scene.name + ".json");
    return true;
  } catch (const InputError& e) {
    std::cerr << "bench_peers: skipping " << scene.name << " (run scripts/make_models.sh --fine "
              << "to generate its models): " << e.what() << '\n';
    return false;
  }
}

void register_all() {
  // Brute force and the paper's octree only where they finish: at 50k faces per body brute
  // would test 2.5e9 pairs per frame.
  const std::vector<ComparedScene> scenes = {
      {"phase1", {BroadPhase::kBrute, BroadPhase::kOctree, BroadPhase::kBvh}, false},
      {"phase2", {BroadPhase::kBrute, BroadPhase::kOctree, BroadPhase::kBvh}, false},
      {"scaling/phase1_50k", {BroadPhase::kBvh}, true},
  };
  for (const ComparedScene& scene : scenes) {
    if (!available(scene)) continue;
    for (BroadPhase method : scene.methods) {
      for (int threads : {1, 0}) {
        const std::string name = "contact_frame/" + scene.name + "/deformcd-" +
                                 std::string(broadphase_name(method)) +
                                 (threads == 1 ? "/threads:1" : "/threads:all");
        benchmark::RegisterBenchmark(name.c_str(), deformcd_method, scene.name, method, threads)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
      }
    }
    for (const std::string& p : bench::peer_names()) {
      const std::string name = "contact_frame/" + scene.name + "/" + p;
      benchmark::RegisterBenchmark(name.c_str(), peer, scene.name, p)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
