#pragma once
// What `deformcd render` and `deformcd view` share: a scene loaded for a run of a given length,
// the box its bodies stay within (for a fixed camera), and the broad phase to show.

#include <optional>
#include <string>
#include <vector>

#include "deformcd/body.h"
#include "deformcd/collision.h"
#include "deformcd/scene.h"
#include "deformcd/simulation_state.h"

namespace deformcd::app {

struct ViewScene {
  Scene scene;
  int total_frames = 0;  // the run's length: the bodies' paths span it
  std::vector<BodyInit> bodies;
  Bounds swept;  // every body over the whole run (render::swept_bounds)
};

// Reads `file` and builds its bodies for a run of `frames` frames (--frames; default: the
// scene's), saying so on stderr. Throws UsageError when frames is below 1, InputError for a bad
// scene.
[[nodiscard]] ViewScene load_view_scene(const std::string& file, const std::optional<int>& frames);

// --broadphase if given, else the scene's collision.broadphase.
[[nodiscard]] BroadPhase view_broadphase(const std::optional<std::string>& option,
                                         const Scene& scene);

}  // namespace deformcd::app
