// deformcd against the libraries a user would pick instead, on identical frames: the contact
// frames of the shipped phase scenes and, when its models have been generated
// (scripts/make_models.sh --fine), of scenes/scaling/phase1_50k (about 50k faces per body);
// positions replayed on the CPU backend, each contestant finding every intersecting
// surface-triangle pair between the two bodies. Every row's name ends in its thread count.
//   deformcd-<method>: a public deformcd::Detector (CPU backend) over the two meshes, reading the
//        caller's xyz arrays in place: each frame's positions are written into them (untimed, as
//        the caller's simulation would), then detect() and counts() are timed (box update or
//        refit included). "/threads:1" runs it on one thread, "/threads:all" on every core.
//   fcl-aabb-contacts, fcl-aabb, fcl-obbrss: FCL 0.7, a BVHModel per body refitted each frame,
//        collide() with contact points, pairs only, and pairs only over OBBRSS;
//        fcl-aabb-update-contacts: this benchmark's first FCL row, swept leaves and contact
//        points (fcl_contestant.cpp).
//   cgal, cgal-cutoff10, cgal-parallel: CGAL 5.5 box_intersection_d over the triangles' boxes
//        (cutoff 2000 as CGAL's Polygon_mesh_processing, the default 10, and 2000 with
//        Parallel_tag on every core), then do_intersect on Epick triangles (cgal_contestant.cpp).
//   bullet-dbvt: Bullet 3.24, a btDbvt per mesh updated as btSoftBody updates its face tree,
//        collideTT, then the same do_intersect (bullet_contestant.cpp).
// refit/<scene>/deformcd-bvh: the bvh pass's refit alone (refit_rows.h), on the same frames.
// One iteration runs every kept contact frame once; the time reported is per frame (wall clock,
// the iteration's time divided by the frames), "contacts" is the number found over the frames,
// "threads" the threads the row runs on.
// Before its timed loop, each row's pairs are collected once over the frames and compared pair
// for pair with deformcd's (bvh): "differ" pairs are in one list only, "zone" of them are pairs
// where deformcd's float answer is not the exact one (CGAL's) but lies in its uncertain zone,
// "peer_off" pairs where the contestant is off the exact answer, "unexplained" the rest. An
// unexplained pair, or more differing pairs than 0.5 % of deformcd's, fails the row (and the
// program exits 1): the contestants must be doing the same work ("replay_contacts": what
// deformcd's bvh found while replaying the scene).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "contact_frames.h"
#include "deformcd/detector.h"
#include "deformcd/error.h"
#include "deformcd/scene.h"
#include "pair_check.h"
#include "peer_contestants.h"
#include "refit_rows.h"

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

// Writes a frame's positions into the caller's arrays in place (the detector reads them there).
void write_positions(bench::FramePositions& current, const bench::FramePositions& positions) {
  for (std::size_t m = 0; m < current.size(); ++m)
    std::copy(positions[m].begin(), positions[m].end(), current[m].begin());
}

// deformcd's pairs on the scene's frames (bvh, every core): the reference of every row.
const bench::FramePairs& reference_pairs(const std::string& scene) {
  static std::map<std::string, bench::FramePairs> cache;
  auto it = cache.find(scene);
  if (it != cache.end()) return it->second;
  const bench::ContactFrames& f = frames_of(scene);
  Detector detector(f.meshes, {.backend = BackendKind::kCpu, .broadphase = BroadPhase::kBvh});
  bench::FramePositions current = f.positions.front();
  for (std::size_t m = 0; m < current.size(); ++m)
    detector.set_positions(m, std::span<const glm::vec3>(current[m]));
  bench::FramePairs pairs;
  for (const bench::FramePositions& positions : f.positions) {
    write_positions(current, positions);
    detector.detect();
    std::vector<bench::FacePair>& frame = pairs.emplace_back();
    for (const Contact& c : detector.contacts())
      frame.emplace_back(c.a.face, c.b.face);
  }
  return cache.emplace(scene, std::move(pairs)).first->second;
}

bool g_failed = false;  // a row's pair check failed: main returns 1

// A row's pairs over the frames, and the triangle pairs it tested (0 when its library does
// not say).
struct Collected {
  bench::FramePairs pairs;
  std::size_t candidates = 0;
};

struct RowCheck {
  bench::PairCheck pairs;
  std::size_t candidates = 0;
};

// Checks a row's pairs (collected once per row, untimed) against deformcd's, sets the check's
// counters, and fails the row loudly when the two did not do the same work.
void check(benchmark::State& state, const std::string& row, const std::string& scene,
           const std::function<Collected()>& collect) {
  static std::map<std::string, RowCheck> cache;
  auto it = cache.find(row);
  if (it == cache.end()) {
    Collected collected = collect();
    for (std::vector<bench::FacePair>& frame : collected.pairs)
      std::sort(frame.begin(), frame.end());
    const RowCheck checked = {
        bench::check_pairs(frames_of(scene), reference_pairs(scene), collected.pairs),
        collected.candidates};
    it = cache.emplace(row, checked).first;
    const bench::PairCheck& c = it->second.pairs;
    std::cerr << "bench_peers: " << row << ": " << c.found << " pairs, deformcd " << c.reference
              << ", " << c.differ << " in one list only (" << c.zone
              << " in deformcd's uncertain zone, " << c.contestant_off
              << " where the contestant is off the exact answer, " << c.unexplained
              << " unexplained)\n";
  }
  const bench::PairCheck& c = it->second.pairs;
  if (it->second.candidates != 0)
    state.counters["candidates"] = static_cast<double>(it->second.candidates);
  state.counters["differ"] = static_cast<double>(c.differ);
  state.counters["zone"] = static_cast<double>(c.zone);
  state.counters["peer_off"] = static_cast<double>(c.contestant_off);
  state.counters["unexplained"] = static_cast<double>(c.unexplained);
  if (!c.acceptable()) {
    g_failed = true;
    const std::string message =
        row + ": its pairs are not deformcd's: " + std::to_string(c.differ) +
        " in one list only of " + std::to_string(c.reference) + ", " +
        std::to_string(c.unexplained) + " unexplained" +
        (c.first_unexplained.empty() ? "" : " (first: " + c.first_unexplained + ")");
    std::cerr << "bench_peers: error: " << message << '\n';
    state.SkipWithError(message.c_str());
  }
}

void report(benchmark::State& state, const bench::ContactFrames& f, std::size_t found,
            int threads) {
  state.counters["contacts"] =
      benchmark::Counter(static_cast<double>(found), benchmark::Counter::kAvgIterations);
  state.counters["replay_contacts"] = 0.0;
  for (std::size_t c : f.contacts)
    state.counters["replay_contacts"] += static_cast<double>(c);
  state.counters["frames"] = static_cast<double>(f.positions.size());
  state.counters["faces"] = static_cast<double>(f.face_count());
  state.counters["threads"] =
      threads == 0 ? static_cast<double>(std::thread::hardware_concurrency()) : threads;
  // Wall time per frame (one iteration covers every frame): frames per second, inverted.
  state.counters["per_frame"] = benchmark::Counter(
      static_cast<double>(f.positions.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void deformcd_method(benchmark::State& state, const std::string& row, const std::string& scene,
                     BroadPhase method, int threads) {
  const bench::ContactFrames& f = frames_of(scene);
  Detector detector(f.meshes,
                    {.backend = BackendKind::kCpu, .broadphase = method, .threads = threads});
  // The caller's arrays, read in place by every detect().
  bench::FramePositions current = f.positions.front();
  for (std::size_t m = 0; m < current.size(); ++m)
    detector.set_positions(m, std::span<const glm::vec3>(current[m]));
  detector.prepare();
  check(state, row, scene, [&] {
    Collected out;
    for (const bench::FramePositions& positions : f.positions) {
      write_positions(current, positions);
      detector.detect();
      std::vector<bench::FacePair>& frame = out.pairs.emplace_back();
      for (const Contact& c : detector.contacts())
        frame.emplace_back(c.a.face, c.b.face);
      out.candidates += detector.counts().candidates;
    }
    return out;
  });
  std::size_t found = 0;
  for (auto _ : state) {
    for (const bench::FramePositions& positions : f.positions) {
      state.PauseTiming();
      write_positions(current, positions);
      state.ResumeTiming();
      detector.detect();
      found += detector.counts().contacts;
    }
  }
  report(state, f, found, threads);
}

void peer(benchmark::State& state, const std::string& row, const std::string& scene,
          const bench::PeerInfo& info) {
  const bench::ContactFrames& f = frames_of(scene);
  std::unique_ptr<bench::PeerContestant> contestant =
      bench::make_peer(info.name, f.meshes, f.positions.front());
  check(state, row, scene, [&] {
    Collected out;
    for (const bench::FramePositions& positions : f.positions) {
      (void)contestant->detect(positions, &out.pairs.emplace_back());
      out.candidates += contestant->candidates();
    }
    return out;
  });
  std::size_t found = 0;
  for (auto _ : state) {
    for (const bench::FramePositions& positions : f.positions)
      found += contestant->detect(positions, nullptr);
  }
  report(state, f, found, info.threads);
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
        benchmark::RegisterBenchmark(name.c_str(), deformcd_method, name, scene.name, method,
                                     threads)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
      }
    }
    for (int threads : {1, 0}) {
      const std::string name =
          "refit/" + scene.name + "/deformcd-bvh" + (threads == 1 ? "/threads:1" : "/threads:all");
      benchmark::RegisterBenchmark(
          name.c_str(),
          [](benchmark::State& state, const std::string& scene_name, int t) {
            bench::refit_row(state, frames_of(scene_name), t);
          },
          scene.name, threads)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
    for (const bench::PeerInfo& p : bench::peers()) {
      const std::string name = "contact_frame/" + scene.name + "/" + p.name +
                               (p.threads == 1 ? "/threads:1" : "/threads:all");
      benchmark::RegisterBenchmark(name.c_str(), peer, name, scene.name, p)
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
  return g_failed ? 1 : 0;
}
