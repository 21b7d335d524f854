#include "view_scene.h"

#include "deformcd/error.h"
#include "deformcd/render/camera.h"
#include "model_input.h"

namespace deformcd::app {

ViewScene load_view_scene(const std::string& file, const std::optional<int>& total_frames) {
  ViewScene view;
  view.scene = read_scene(file);
  view.total_frames = total_frames.value_or(view.scene.settings.frames);
  if (view.total_frames < 1) throw Error("--total-frames must be at least 1");
  view.bodies = make_scene_bodies(view.scene, load_model_argument, view.total_frames);
  const double seconds = view.scene.settings.dt * view.total_frames;
  view.swept = render::swept_bounds(view.bodies, static_cast<float>(seconds));
  return view;
}

BroadPhase view_broadphase(const std::optional<std::string>& option, const Scene& scene) {
  return parse_broadphase(option.value_or(scene.collision.broadphase));
}

}  // namespace deformcd::app
