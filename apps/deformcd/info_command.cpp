// `deformcd info`: statistics of a model (as a body would be built from it), or of the GPU.

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "deformcd/body.h"
#include "deformcd/error.h"
#include "model_input.h"
#include "usage_error.h"
#ifdef DEFORMCD_HAS_GL
#include "gpu_info_command.h"
#endif

namespace deformcd::app {

namespace {

struct InfoOptions {
  std::string model;
  bool gpu = false;
  bool json = false;
  bool merge_edges = false;
};

std::size_t surface_node_count(const Body& body) {
  std::vector<bool> on_surface(body.positions.size(), false);
  for (const gpu::Face& f : body.faces)
    on_surface[f.a] = on_surface[f.b] = on_surface[f.c] = true;
  return static_cast<std::size_t>(std::count(on_surface.begin(), on_surface.end(), true));
}

int print_model_info(const InfoOptions& o) {
  TetMesh mesh = load_model_argument(o.model);
  BodyOptions body_options;
  body_options.merge_shared_edges = o.merge_edges;
  const Body body = build_body(mesh, body_options, o.model);
  const Bounds b = compute_bounds(body);
  const std::size_t surface_nodes = surface_node_count(body);

  if (o.json) {
    nlohmann::json j;
    j["model"] = o.model;
    j["nodes"] = body.positions.size();
    j["surface_nodes"] = surface_nodes;
    j["tetrahedra"] = body.tetrahedra.size();
    j["faces"] = body.faces.size();
    j["springs"] = body.springs.size();
    j["volume"] = body.volume;
    j["bounds"] = {{"min", {b.min.x, b.min.y, b.min.z}}, {"max", {b.max.x, b.max.y, b.max.z}}};
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  std::cout << "model          " << o.model << '\n'
            << "nodes          " << body.positions.size() << " (" << surface_nodes
            << " on the surface)\n"
            << "tetrahedra     " << body.tetrahedra.size() << '\n'
            << "surface faces  " << body.faces.size() << '\n'
            << "springs        " << body.springs.size()
            << (o.merge_edges ? " (shared edges merged)" : " (6 per tetrahedron)") << '\n'
            << std::setprecision(6) << "volume         " << body.volume << '\n'
            << "bounds         [" << b.min.x << ", " << b.min.y << ", " << b.min.z << "] .. ["
            << b.max.x << ", " << b.max.y << ", " << b.max.z << "]\n";
  return 0;
}

}  // namespace

Command add_info_command(CLI::App& app) {
  auto o = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "info",
      "Print a model's statistics (nodes, tetrahedra, surface faces, springs, bounds), "
      "or the GPU's with --gpu");
  cmd->add_option("model", o->model,
                  "TetGen prefix (PREFIX.node/.ele) or surface file (.off .obj .stl .ply), meshed "
                  "as a scene meshes it by default (TetGen -pq2Y)");
  cmd->add_flag("--gpu", o->gpu, "Describe the OpenGL device and its compute limits");
  cmd->add_flag("--json", o->json, "Print one JSON object");
  cmd->add_flag("--merge-edges", o->merge_edges,
                "One spring per distinct edge instead of one per tetrahedron edge");
  return [o]() -> int {
    if (o->gpu) {
#ifdef DEFORMCD_HAS_GL
      return run_gpu_info(std::cout, o->json);
#else
      std::cerr << "deformcd: this build has no OpenGL backend (-DDEFORMCD_WITH_GL=OFF); "
                   "the CPU backend is available\n";
      return 1;
#endif
    }
    if (o->model.empty()) throw UsageError("give a MODEL, or --gpu");
    return print_model_info(*o);
  };
}

}  // namespace deformcd::app
