#include "contact_frames.h"

#include "cpu/cpu_collision.h"
#include "cpu/cpu_simulation.h"
#include "deformcd/io.h"
#include "deformcd/scene.h"

namespace deformcd::bench {

ContactFrames contact_frames(const std::string& name, int frames, int keep) {
  const Scene scene = read_scene(std::string(DEFORMCD_SOURCE_DIR) + "/scenes/" + name + ".json");
  ContactFrames out;
  out.state = assemble_world(make_scene_bodies(scene, read_tetgen, frames));
  const StepSettings settings = step_settings(scene.settings);
  const float h = settings.dt / static_cast<float>(settings.substeps);
  const sim::SubstepConstants constants{h, settings.gravity,
                                        std::exp(-settings.velocity_damping * h)};
  cpu::CpuSimulation sim;
  sim.upload(out.state);
  cpu::CpuCollision collision(sim);
  collision.upload(out.state);
  std::vector<std::vector<glm::vec4>> all;
  std::vector<std::size_t> counts;
  for (int f = 0; f < frames; ++f) {
    for (int s = 0; s < settings.substeps; ++s)
      sim.substep(constants);
    collision.detect(BroadPhase::kBvh);  // the fastest; every method finds the same pairs
    const std::uint32_t found = collision.counters().face_pairs;
    if (found == 0) continue;
    all.push_back(sim.state().positions);
    counts.push_back(found);
  }
  const std::size_t n = all.size();
  const std::size_t take = std::min<std::size_t>(n, static_cast<std::size_t>(keep));
  for (std::size_t i = 0; i < take; ++i) {
    const std::size_t k = take == 1 ? n / 2 : i * (n - 1) / (take - 1);
    out.positions.push_back(all[k]);
    out.contacts.push_back(counts[k]);
  }
  return out;
}

}  // namespace deformcd::bench
