// `deformcd view SCENE`: an interactive window that runs a scene on the GL backend in the
// window's own context and draws it from the simulation's buffers every frame.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.h"
#include "deformcd/error.h"
#include "deformcd/gl/context.h"
#include "deformcd/render/image.h"
#include "deformcd/render/offscreen_target.h"
#include "deformcd/render/scene_renderer.h"
#include "deformcd/world.h"
#include "option_values.h"
#include "output_paths.h"
#include "progress.h"
#include "usage_error.h"
#include "view_scene.h"
#include "viewer_window.h"

namespace deformcd::app {

namespace {

struct ViewOptions {
  std::string scene;
  std::optional<int> frames;  // the run's length
  std::optional<std::string> broadphase;
  std::optional<int> quit_after;
  std::string screenshot;
};

// What the viewer shows and lets the user change.
struct ViewerState {
  bool paused = false;
  render::RenderMode mode = render::RenderMode::kWireframe;
  BroadPhase broadphase = BroadPhase::kBvh;
};

// The broad phases that detect, in their listed order (broadphase_names()), then none.
BroadPhase next_broadphase(BroadPhase method) {
  const std::vector<std::string>& names = broadphase_names();
  if (method == BroadPhase::kNone) return parse_broadphase(names.front());
  for (std::size_t i = 0; i + 1 < names.size(); ++i) {
    if (parse_broadphase(names[i]) == method) return parse_broadphase(names[i + 1]);
  }
  return BroadPhase::kNone;
}

std::string window_title(const std::string& scene, const World& world, int total_frames,
                         const ViewerState& state) {
  const FrameTimes& t = world.last_frame_times();
  const std::uint64_t contacts = world.collision_counts().contacts;
  char times[96];
  std::snprintf(times, sizeof times, "sim %.1f ms, collision %.1f ms", 1000.0 * t.simulation_s,
                1000.0 * t.collision_s);
  std::ostringstream title;
  title << "deformcd view - " << scene << " - frame " << world.frame() << "/" << total_frames
        << " - " << times << " - " << contacts << " contacts - "
        << broadphase_name(state.broadphase) << " - "
        << (state.mode == render::RenderMode::kWireframe ? "wireframe" : "shaded");
  if (world.frame() >= total_frames) {
    title << " [end of run]";
  } else if (state.paused) {
    title << " [paused]";
  }
  return title.str();
}

int view(const ViewOptions& o) {
  if (o.frames) check_at_least("--frames", *o.frames, 1);
  if (o.quit_after) check_at_least("--quit-after", *o.quit_after, 0);
  if (!o.screenshot.empty()) check_output_file("--screenshot", o.screenshot);
  // The window first: without a display, say so before the scene takes time to load.
  ViewerWindow window(1280, 720, "deformcd view - " + o.scene);
  const ViewScene scene = load_view_scene(o.scene, o.frames);
  if (o.quit_after && *o.quit_after > scene.total_frames) {
    throw UsageError("--quit-after " + std::to_string(*o.quit_after) + ": the run has " +
                     std::to_string(scene.total_frames) + " frames (--frames sets its length)");
  }
  ViewerState state;
  state.broadphase = view_broadphase(o.broadphase, scene.scene);

  const std::unique_ptr<gl::Context> context =
      gl::adopt_current_context([&window] { window.make_current(); });
  WorldOptions options;
  options.backend = BackendKind::kGl;
  options.gl_context = context.get();
  options.broadphase = state.broadphase;
  options.self_collision = scene.scene.collision.self;
  options.response = scene.scene.response;
  options.measure_stage_times = true;
  status("starting the GL backend");
  World world(scene.bodies, step_settings(scene.scene.settings), options);
  if (!world.notice().empty()) std::cerr << "deformcd: " << world.notice() << '\n';
  if (state.broadphase != BroadPhase::kNone) world.detect_collisions();  // the initial pose

  int width = 0, height = 0;
  window.framebuffer_size(width, height);
  const auto framing = [&] {
    const float aspect = height > 0 ? static_cast<float>(width) / static_cast<float>(height) : 1.0f;
    return render::Camera::framing(scene.swept, aspect);
  };
  render::Camera camera = framing();
  const render::SceneRenderer renderer(world);
  const auto draw = [&] {
    render::DrawOptions look;
    look.mode = state.mode;
    look.show_collisions = state.broadphase != BroadPhase::kNone;
    renderer.draw(camera, width, height, look);
  };

  while (true) {
    const bool idle = state.paused || world.frame() >= scene.total_frames;
    const ViewerInput in = window.poll(idle ? 0.05 : 0.0);
    if (in.quit) break;
    window.framebuffer_size(width, height);
    const float pixels = static_cast<float>(std::max(1, window.window_height()));
    camera.orbit(-0.3f * static_cast<float>(in.orbit_x), 0.3f * static_cast<float>(in.orbit_y));
    camera.pan(-static_cast<float>(in.pan_x) / pixels, static_cast<float>(in.pan_y) / pixels);
    camera.zoom(std::pow(0.9f, static_cast<float>(in.scroll)));
    if (in.reset_camera) camera = framing();
    if (in.toggle_pause) state.paused = !state.paused;
    if (in.toggle_mode) {
      state.mode = state.mode == render::RenderMode::kWireframe ? render::RenderMode::kShaded
                                                                : render::RenderMode::kWireframe;
    }
    if (in.cycle_broadphase) {
      state.broadphase = next_broadphase(state.broadphase);
      world.set_broadphase(state.broadphase);
      // Show the new method's result at once, also when paused.
      if (state.broadphase != BroadPhase::kNone) world.detect_collisions();
    }
    if ((!state.paused || in.step_once) && world.frame() < scene.total_frames) world.step();

    draw();
    window.swap_buffers();
    window.set_title(window_title(o.scene, world, scene.total_frames, state));
    if (o.quit_after && world.frame() >= *o.quit_after) break;
  }
  if (!o.screenshot.empty()) {
    // The last frame shown, drawn again: the swap left the back buffer's contents undefined.
    draw();
    render::write_png(o.screenshot, render::read_framebuffer(width, height));
    std::cout << "screenshot " << o.screenshot << '\n';
  }
  std::cout << "view: frame " << world.frame() << ", " << world.collision_counts().contacts
            << " contacts (" << broadphase_name(state.broadphase) << ")\n";
  return 0;
}

}  // namespace

Command add_view_command(CLI::App& app) {
  auto o = std::make_shared<ViewOptions>();
  CLI::App* cmd = app.add_subcommand(
      "view",
      "Watch a scene in a window (left drag orbit, wheel zoom, right/middle drag pan, space "
      "pause, N step, B broad phase, W wireframe/shaded, R reset camera, Esc/Q quit)");
  cmd->add_option("scene", o->scene, "Scene file (JSON)")->required();
  add_frames_option(cmd, o->frames);
  add_broadphase_option(cmd, o->broadphase, true);
  cmd->add_option("--quit-after", o->quit_after,
                  "Quit once this frame is shown (e.g. for scripts and tests)");
  cmd->add_option("--screenshot", o->screenshot,
                  "Write the last frame shown, when the viewer quits, as a PNG file");
  return [o]() { return view(*o); };
}

}  // namespace deformcd::app
