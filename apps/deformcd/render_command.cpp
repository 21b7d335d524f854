// `deformcd render SCENE`: runs a scene on a headless GL context and writes PNG images of
// chosen frames, drawn straight from the simulation's buffers.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <system_error>
#include <vector>

#include "commands.h"
#include "deformcd/error.h"
#include "deformcd/gl/context.h"
#include "deformcd/render/offscreen_target.h"
#include "deformcd/render/scene_renderer.h"
#include "deformcd/world.h"
#include "option_values.h"
#include "output_paths.h"
#include "progress.h"
#include "response_summary.h"
#include "usage_error.h"
#include "video_encoder.h"
#include "view_scene.h"

namespace deformcd::app {

namespace {

namespace fs = std::filesystem;

struct RenderOptions {
  std::string scene;
  std::vector<int> at;  // the frames to write
  std::string out;
  std::string size = "1280x720";
  std::optional<std::string> broadphase;
  bool shaded = false;
  bool every_frame = false;
  std::string backend = "gl";
  std::optional<int> frames;  // the run's length
  std::string video;
};

struct ImageSize {
  int width = 0;
  int height = 0;
};

ImageSize parse_size(const std::string& text) {
  ImageSize size;
  char x = 0;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &size.width, &x, &size.height, &extra) != 3 ||
      (x != 'x' && x != 'X') || size.width < 1 || size.height < 1 || size.width > 16384 ||
      size.height > 16384) {
    throw UsageError("--size '" + text + "': expected WIDTHxHEIGHT in pixels, e.g. 1280x720");
  }
  return size;
}

// The frames to write, increasing, each checked against the run's length.
std::vector<int> chosen_frames(const RenderOptions& o, int total_frames) {
  if (o.every_frame || !o.video.empty()) {
    std::vector<int> all(static_cast<std::size_t>(total_frames) + 1);
    for (int f = 0; f <= total_frames; ++f)
      all[static_cast<std::size_t>(f)] = f;
    return all;
  }
  const std::set<int> unique(o.at.begin(), o.at.end());
  for (int f : unique) {
    if (f < 0 || f > total_frames) {
      throw UsageError("--at: frame " + std::to_string(f) + " is outside the run (0 to " +
                       std::to_string(total_frames) + "; frame 0 is the initial pose; --frames " +
                       "sets the run's length)");
    }
  }
  return {unique.begin(), unique.end()};
}

std::string image_name(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05d.png", frame);
  return name;
}

std::unique_ptr<gl::Context> headless_context() {
  try {
    return gl::create_headless_context();
  } catch (const GlError& e) {
    throw GlError(std::string("deformcd render draws from the simulation's OpenGL buffers and "
                              "needs an OpenGL 4.3 context, which could not be had:\n") +
                  e.what());
  }
}

int render(const RenderOptions& o) {
  // Everything that can be checked without the scene is checked first, so mistakes fail fast.
  if (o.at.empty() && !o.every_frame && o.video.empty()) {
    throw UsageError("say which frames to write: --at K1,K2,... or --every-frame");
  }
  if (!o.at.empty() && (o.every_frame || !o.video.empty())) {
    throw UsageError(o.every_frame ? "--at and --every-frame exclude each other"
                                   : "--video encodes every frame; give it without --at");
  }
  if (o.frames) check_at_least("--frames", *o.frames, 1);
  const ImageSize size = parse_size(o.size);
  check_output_directory("--out", o.out);
  std::optional<fs::path> ffmpeg;
  if (!o.video.empty()) {
    // ffmpeg picks the container from the extension, and an MP4 needs a seekable file.
    if (o.video == "-") throw UsageError("--video - : give a file name (an .mp4 needs a file)");
    check_output_file("--video", o.video);
    ffmpeg = require_program("--video", o.video, "ffmpeg",
                             "install ffmpeg, or write the frames with --every-frame and encode " +
                                 o.out + "/frame_%05d.png with another tool");
  }
  const fs::path out_dir(o.out);

  const ViewScene view = load_view_scene(o.scene, o.frames);
  const std::vector<int> frames = chosen_frames(o, view.total_frames);
  const BroadPhase broadphase = view_broadphase(o.broadphase, view.scene);

  status("starting OpenGL");
  const std::unique_ptr<gl::Context> context = headless_context();
  WorldOptions options;
  options.backend = BackendKind::kGl;
  options.gl_context = context.get();
  // Collision detection runs only on the frames drawn (the simulation does not depend on it).
  options.broadphase = BroadPhase::kNone;
  options.self_collision = view.scene.collision.self;
  options.response = view.scene.response;
  World world(view.bodies, step_settings(view.scene.settings), options);
  if (!world.notice().empty()) std::cerr << "deformcd: " << world.notice() << '\n';

  const float aspect = static_cast<float>(size.width) / static_cast<float>(size.height);
  const render::Camera camera = render::Camera::framing(view.swept, aspect);
  const render::SceneRenderer renderer(world);
  const render::OffscreenTarget target(size.width, size.height);
  render::DrawOptions draw;
  draw.mode = o.shaded ? render::RenderMode::kShaded : render::RenderMode::kWireframe;
  draw.show_collisions = broadphase != BroadPhase::kNone;
  create_output_directory("--out", o.out);

  ResponseTally response;
  Progress progress("rendering", frames.back());
  progress.update(0);
  for (int frame : frames) {
    while (world.frame() < frame) {
      world.step();
      if (world.responds()) response.add(world.frame(), world.response_counts());
      progress.update(world.frame());
    }
    std::uint64_t contacts = 0;
    if (broadphase != BroadPhase::kNone) {
      world.set_broadphase(broadphase);
      world.detect_collisions();
      contacts = world.collision_counts().contacts;
      world.set_broadphase(BroadPhase::kNone);
    }
    target.bind();
    renderer.draw(camera, size.width, size.height, draw);
    const fs::path file = out_dir / image_name(frame);
    render::write_png(file, target.read());
    progress.clear();
    std::cout << file.string() << "  frame " << frame;
    if (!world.responds()) {
      std::cout << "  " << contacts << " contacts";
    } else {
      // The response keeps surfaces apart: its constraints, not intersections, say it acts.
      std::cout << "  ";
      if (broadphase != BroadPhase::kNone) {
        std::cout << count_of(contacts, "intersecting face pair", "intersecting face pairs")
                  << ", ";
      }
      const ResponseCounts c = world.response_counts();
      std::cout << count_of(c.contact_constraints(), "contact constraint", "contact constraints");
    }
    std::cout << std::endl;
  }
  if (world.responds()) {
    std::cout << "response: "
              << describe_response(response, world.body_count(),
                                   view.scene.response->sleep.has_value())
              << '\n';
  }
  if (ffmpeg) {
    const double fps = 1.0 / view.scene.settings.dt;
    encode_video(*ffmpeg, out_dir, frames.front(), std::round(fps * 1000.0) / 1000.0, o.video);
    std::cout << o.video << "  " << frames.size() << " frames\n";
  }
  return 0;
}

}  // namespace

Command add_render_command(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render", "Run a scene headless on OpenGL and write PNG images of chosen frames");
  cmd->add_option("scene", o->scene, "Scene file (JSON)")->required();
  add_frames_option(cmd, o->frames);
  cmd->add_option("--at", o->at,
                  "Frames to write, comma-separated (0 = the initial pose), e.g. 0,100,200")
      ->delimiter(',');
  cmd->add_flag("--every-frame", o->every_frame, "Write every frame of the run, 0..N");
  cmd->add_option("-o,--out", o->out, "Directory for the images (created): DIR/frame_00042.png")
      ->required();
  cmd->add_option("--size", o->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  add_broadphase_option(cmd, o->broadphase, true);
  cmd->add_flag("--shaded", o->shaded,
                "Lit faces instead of the paper's wireframe (colliding faces coloured alike)");
  cmd->add_option("--backend", o->backend,
                  "gl, the only one: the images are drawn from the simulation's GL buffers")
      ->check(CLI::Validator(
          [](std::string& name) -> std::string {
            if (name == "gl") return {};
            return "render draws the world from its OpenGL buffers, so it runs on the GL "
                   "backend only; the " +
                   name + " backend has no buffers to draw";
          },
          "gl"))
      ->capture_default_str();
  cmd->add_option("--video", o->video,
                  "Also encode every frame into this video (needs ffmpeg on PATH)");
  return [o]() { return render(*o); };
}

}  // namespace deformcd::app
