// deformcd: command-line front end. Each subcommand lives in its own *_command.cpp.

#include <exception>
#include <iostream>

#include "commands.h"
#include "deformcd/error.h"

int main(int argc, char** argv) {
  CLI::App app{
      "deformcd: deformable-body simulation and parallel collision detection\n"
      "(OpenGL 4.3 compute shaders, with a multithreaded CPU backend)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "deformcd " DEFORMCD_VERSION);

  const deformcd::app::Command info = deformcd::app::add_info_command(app);
  const deformcd::app::Command tetra = deformcd::app::add_tetra_command(app);
  const deformcd::app::Command run = deformcd::app::add_run_command(app);
  const deformcd::app::Command bench = deformcd::app::add_bench_command(app);
  const deformcd::app::Command collide = deformcd::app::add_collide_command(app);
#ifdef DEFORMCD_HAS_RENDER
  const deformcd::app::Command render = deformcd::app::add_render_command(app);
  const deformcd::app::Command view = deformcd::app::add_view_command(app);
#endif

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (app.got_subcommand("info")) return info();
    if (app.got_subcommand("tetra")) return tetra();
    if (app.got_subcommand("run")) return run();
    if (app.got_subcommand("bench")) return bench();
    if (app.got_subcommand("collide")) return collide();
#ifdef DEFORMCD_HAS_RENDER
    if (app.got_subcommand("render")) return render();
    if (app.got_subcommand("view")) return view();
#endif
  } catch (const deformcd::Error& e) {
    std::cerr << "deformcd: error: " << e.what() << '\n';
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "deformcd: unexpected error: " << e.what() << '\n';
    return 2;
  }
  return 0;
}
