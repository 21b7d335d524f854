// make_models: source surface -> repaired, (refined,) decimated, normalized closed surface (OFF)
// ready for `deformcd tetra --preserve-surface`. Developer tool; links CGAL (GPL/LGPL), never
// shipped with the library. scripts/make_models.sh runs it for the paper's four models.

#include <exception>
#include <filesystem>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "deformcd/error.h"
#include "surface_checks.h"
#include "surface_decimation.h"
#include "surface_output.h"
#include "surface_repair.h"
#include "surface_subdivision.h"

namespace {

struct Options {
  std::filesystem::path input;
  std::filesystem::path output;
  std::size_t faces = 0;
  std::string policy = "lt";
};

void print_repair(const make_models::RepairSummary& s) {
  std::cout << "  repaired:   " << s.components_removed << " stray components removed, "
            << s.holes_filled << " holes filled (" << s.hole_faces_added << " faces"
            << (s.holes_unfaired != 0 ? ", " + std::to_string(s.holes_unfaired) + " unfaired" : "")
            << "), " << s.degenerate_faces_removed << " degenerate faces removed"
            << (s.reversed ? ", orientation reversed" : "")
            << (s.self_intersections_repaired ? ", self-intersections repaired" : "") << '\n';
}

int run(const Options& o) {
  using namespace make_models;
  if (o.faces < 4 || o.faces % 2 != 0) {
    throw deformcd::Error(
        "--faces must be even and >= 4 (a closed triangle surface has an even "
        "face count)");
  }
  const CollapsePolicy policy = parse_collapse_policy(o.policy);
  std::cout << o.input.filename().string() << '\n';
  RepairSummary summary;
  Mesh mesh = load_and_repair(o.input, summary);
  print_repair(summary);
  std::cout << "  source:     " << describe(summary.result) << '\n';

  // Sources coarser than the target (the finer scaling models) are refined first.
  if (const int passes = subdivide_to_at_least(mesh, o.faces); passes > 0) {
    std::cout << "  subdivided: " << passes << " Loop pass" << (passes > 1 ? "es" : "") << ", "
              << mesh.number_of_faces() << " faces\n";
  }
  const std::size_t edges_removed = decimate(mesh, o.faces, policy);
  normalize_to_unit_box(mesh);
  const SurfaceReport report = inspect(mesh);
  std::cout << "  decimated:  " << describe(report) << " (" << edges_removed
            << " edges removed, policy " << o.policy << ")\n";
  if (mesh.number_of_faces() != o.faces) {
    throw deformcd::Error(o.input.string() + ": decimation stopped at " +
                          std::to_string(mesh.number_of_faces()) + " faces, not " +
                          std::to_string(o.faces));
  }
  if (!is_clean(report)) {
    throw deformcd::Error(o.input.string() + ": decimated surface is not clean (" +
                          describe(report) + "); try the other --policy or another --faces");
  }
  write_off(mesh, o.output);
  std::cout << "  wrote " << o.output.string() << '\n';
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Repair, decimate and normalize a surface for `deformcd tetra --preserve-surface`"};
  Options o;
  app.add_option("input", o.input, "Source surface (OFF)")->required()->check(CLI::ExistingFile);
  app.add_option("-o,--output", o.output, "Output OFF file")->required();
  app.add_option("--faces", o.faces, "Target triangle count (even)")->required();
  app.add_option("--policy", o.policy,
                 "Edge-collapse policy: lt (Lindstrom-Turk) or gh "
                 "(Garland-Heckbert)")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::cerr << "make_models: " << e.what() << '\n';
    return 1;
  }
}
