#include "view_scene.h"

#include "deformcd/error.h"
#include "deformcd/render/camera.h"
#include "model_input.h"
#include "option_values.h"
#include "progress.h"

namespace deformcd::app {

ViewScene load_view_scene(const std::string& file, const std::optional<int>& frames) {
  ViewScene view;
  if (frames) check_at_least("--frames", *frames, 1);
  status("reading " + file);
  view.scene = read_scene(file);
  view.total_frames = frames.value_or(view.scene.settings.frames);
  status("building " + count_of(view.scene.bodies.size(), "body", "bodies"));
  view.bodies = make_scene_bodies(view.scene, load_scene_model, view.total_frames);
  const double seconds = view.scene.settings.dt * view.total_frames;
  view.swept = render::swept_bounds(view.bodies, static_cast<float>(seconds));
  return view;
}

BroadPhase view_broadphase(const std::optional<std::string>& option, const Scene& scene) {
  return parse_broadphase(option.value_or(scene.collision.broadphase));
}

}  // namespace deformcd::app
