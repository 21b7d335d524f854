// `deformcd tetra`: surface mesh -> TetGen files, in process.

#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "commands.h"
#include "deformcd/body.h"
#include "deformcd/error.h"
#include "deformcd/io.h"
#include "output_paths.h"
#include "usage_error.h"
#ifdef DEFORMCD_HAS_TETGEN
#include "deformcd/tetrahedralize.h"
#endif

namespace deformcd::app {

namespace {

struct TetraOptions {
  std::string input;
  std::string output;
  std::optional<double> quality;
  std::optional<double> max_volume;
  bool preserve_surface = false;
};

}  // namespace

Command add_tetra_command(CLI::App& app) {
  auto o = std::make_shared<TetraOptions>();
  CLI::App* cmd = app.add_subcommand(
      "tetra", "Tetrahedralize a closed surface with TetGen; writes PREFIX.node/.ele/.face");
  cmd->add_option("input", o->input, "Surface mesh (.off .obj .stl .ply)")->required();
  cmd->add_option("-o,--out", o->output, "Output prefix: writes PREFIX.node/.ele/.face")
      ->required();
  cmd->add_option("--quality", o->quality,
                  "Radius-edge ratio bound (TetGen -q; >= 1, smaller is finer; TetGen's "
                  "default 2.0)");
  cmd->add_option("--max-volume", o->max_volume, "Maximum tetrahedron volume (TetGen -a)");
  cmd->add_flag("--preserve-surface", o->preserve_surface,
                "Keep the surface exactly (TetGen -Y): input vertices become the first nodes in "
                "input order, boundary faces are the input triangles");
  return [o]() -> int {
#ifdef DEFORMCD_HAS_TETGEN
    // A prefix of three files: standard output cannot take them.
    if (o->output == "-") throw UsageError("--out - : tetra writes three files; give a prefix");
    for (const char* extension : {".node", ".ele", ".face"})
      check_output_file("--out", o->output + extension);
    const SurfaceMesh surface = read_surface(o->input);
    TetrahedralizeOptions options;
    options.quality = o->quality;
    options.max_volume = o->max_volume;
    options.preserve_surface = o->preserve_surface;
    TetMesh mesh = tetrahedralize(surface, options, o->input);
    // Check it makes a valid body before writing anything.
    const Body body = build_body(mesh, {}, o->input + " (tetrahedralized)");
    mesh.faces.clear();
    for (const gpu::Face& f : body.faces)
      mesh.faces.push_back({f.a, f.b, f.c});
    write_tetgen(mesh, o->output);
    std::cout << "wrote " << o->output << ".node/.ele/.face: " << mesh.nodes.size() << " nodes, "
              << mesh.tetrahedra.size() << " tetrahedra, " << body.faces.size()
              << " surface faces\n";
    return 0;
#else
    throw Error("tetra: this deformcd was built without TetGen (-DDEFORMCD_WITH_TETGEN=OFF)");
#endif
  };
}

}  // namespace deformcd::app
