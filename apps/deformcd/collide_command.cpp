// `deformcd collide A.off B.stl ...`: the intersecting triangle pairs of surface files in their
// poses, through the public Detector (no simulation, no TetGen): open surfaces welcome.

#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "commands.h"
#include "contacts_jsonl.h"
#include "deformcd/detector.h"
#include "deformcd/error.h"
#include "deformcd/io.h"
#include "option_values.h"
#include "output_paths.h"

namespace deformcd::app {

namespace {

struct CollideOptions {
  std::vector<std::string> files;
  bool self = false;
  std::string backend = "auto";
  std::string broadphase = "bvh";
  std::string json_out;
  int threads = 0;
};

// A surface file as a detector mesh, with its positions in float.
struct LoadedSurface {
  CollisionMesh mesh;
  std::vector<glm::vec3> positions;
};

LoadedSurface load_surface(const std::filesystem::path& file, bool self) {
  if (!is_surface_file(file)) {
    throw InputError(file.string(),
                     "not a surface file (collide reads .off, .obj, .stl and .ply surfaces)");
  }
  const SurfaceMesh surface = read_surface(file);
  LoadedSurface loaded;
  loaded.mesh.vertex_count = static_cast<std::uint32_t>(surface.vertices.size());
  loaded.mesh.triangles = surface.triangles;
  loaded.mesh.self_collision = self;
  loaded.mesh.name = file.filename().string();
  loaded.positions.reserve(surface.vertices.size());
  for (const glm::dvec3& v : surface.vertices)
    loaded.positions.emplace_back(v);
  return loaded;
}

int run_collide(const CollideOptions& o) {
  const BackendKind backend = parse_backend(o.backend);
  const BroadPhase method = parse_broadphase(o.broadphase);
  if (method == BroadPhase::kNone) throw Error("collide needs a broad phase other than 'none'");
  check_threads_option(o.threads);
  if (!o.json_out.empty()) check_output_file("--json", o.json_out);
  const SummaryOnStderr summary_on_stderr(writes_stdout({o.json_out}));

  std::vector<LoadedSurface> surfaces;
  std::vector<CollisionMesh> meshes;
  for (const std::string& file : o.files) {
    surfaces.push_back(load_surface(file, o.self));
    meshes.push_back(surfaces.back().mesh);
  }
  Detector detector(std::move(meshes),
                    {.backend = backend, .broadphase = method, .threads = o.threads});
  if (!detector.notice().empty()) std::cerr << "deformcd: " << detector.notice() << '\n';
  for (std::size_t m = 0; m < surfaces.size(); ++m)
    detector.set_positions(m, std::span<const glm::vec3>(surfaces[m].positions));

  // The first pass also builds the hierarchies (on the CPU, from the poses, for either backend)
  // and, on GL, runs each shader for the first time, when the driver compiles it: seconds on a
  // software renderer (2.8 s of a 2.9 s first pass on llvmpipe with Mesa's shader cache off, 47
  // ms with it; 2026-12-03). A second pass on the same poses times what each further pass
  // costs.
  const auto milliseconds_since = [](std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
  };
  auto start = std::chrono::steady_clock::now();
  detector.detect();
  const std::vector<Contact> contacts = detector.contacts();
  const double first_ms = milliseconds_since(start);
  start = std::chrono::steady_clock::now();
  detector.detect();
  (void)detector.contacts();
  const double again_ms = milliseconds_since(start);

  for (std::size_t m = 0; m < surfaces.size(); ++m) {
    std::cout << "mesh " << m << ": " << o.files[m] << ", " << surfaces[m].mesh.vertex_count
              << " vertices, " << surfaces[m].mesh.triangles.size() << " triangles\n";
  }
  std::cout << contacts.size() << " intersecting triangle pair" << (contacts.size() == 1 ? "" : "s")
            << " (" << o.broadphase << " on " << detector.device() << ")\n"
            << std::fixed << std::setprecision(2) << "time: " << first_ms
            << " ms the first pass (the hierarchies' build"
            << (detector.backend_name() == "gl"
                    ? ", and each shader's first run, when the driver compiles it: seconds "
                      "on a software renderer until the driver's shader cache holds them"
                    : "")
            << "), " << again_ms << " ms a second pass on the same poses\n";
  if (!o.json_out.empty()) {
    write_file_atomically(o.json_out, "{\"contacts\":" + contacts_json_array(contacts) + "}\n");
  }
  return 0;
}

}  // namespace

Command add_collide_command(CLI::App& app) {
  auto options = std::make_shared<CollideOptions>();
  CLI::App* cmd = app.add_subcommand(
      "collide",
      "Intersecting triangle pairs of surface files (.off .obj .stl .ply, open surfaces "
      "included) in their given poses; body = the file's position, face = the triangle's index");
  cmd->add_option("files", options->files, "Surface files")->required();
  cmd->add_flag("--self", options->self, "Also test each surface against itself");
  cmd->add_option("--backend", options->backend, "gl, cpu or auto")
      ->check(CLI::IsMember({"auto", "gl", "cpu"}));
  cmd->add_option("--broadphase", options->broadphase, "brute, octree, octree-compact or bvh")
      ->check(CLI::IsMember({"brute", "octree", "octree-compact", "bvh"}));
  cmd->add_option("--threads", options->threads, "CPU threads (0: every core; at most 256)");
  cmd->add_option("--json", options->json_out,
                  "Write {\"contacts\":[...]} (the shape of a `run --contacts` line)");
  return [options] { return run_collide(*options); };
}

}  // namespace deformcd::app
