#include "contact_frames.h"

#include <algorithm>

#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "deformcd/world.h"

namespace deformcd::bench {

ContactFrames contact_frames(const std::string& name, int frames, int keep) {
  const Scene scene = read_scene(std::string(DEFORMCD_SOURCE_DIR) + "/scenes/" + name + ".json");
  World world(make_scene_bodies(scene, read_tetgen, frames), step_settings(scene.settings),
              {.backend = BackendKind::kCpu, .broadphase = BroadPhase::kBvh});
  if (world.body_count() < 2) throw Error("a peer comparison needs two bodies");
  ContactFrames out;
  for (std::size_t b = 0; b < 2; ++b) {
    CollisionMesh mesh = world.detector().mesh(b);
    mesh.self_collision = false;
    out.meshes.push_back(std::move(mesh));
  }
  std::vector<FramePositions> all;
  std::vector<std::size_t> counts;
  for (int f = 0; f < frames; ++f) {
    world.step();
    const std::vector<Contact> contacts = world.contacts();
    const auto found = static_cast<std::size_t>(
        std::count_if(contacts.begin(), contacts.end(),
                      [](const Contact& c) { return c.a.body == 0 && c.b.body == 1; }));
    if (found == 0) continue;
    all.push_back({world.positions(0), world.positions(1)});
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
