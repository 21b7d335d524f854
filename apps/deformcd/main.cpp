// deformcd: command-line front end. Each subcommand lives in its own *_command.cpp.

#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "commands.h"
#include "deformcd/error.h"
#include "usage_error.h"

namespace {

bool is_command(CLI::App& app, const char* name) {
  try {
    (void)app.get_subcommand(name);
    return true;
  } catch (const CLI::OptionNotFound&) {
    return false;
  }
}

// "deformcd run" for the subcommand given, else "deformcd".
std::string command_name(const CLI::App& app) {
  const std::vector<CLI::App*> given = app.get_subcommands();
  return given.empty() ? std::string("deformcd") : "deformcd " + given.front()->get_name();
}

std::string command_list(const CLI::App& app) {
  std::string list;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    list += (list.empty() ? "" : ", ") + sub->get_name();
  return list;
}

int usage_error(const std::string& command, const std::string& message) {
  std::cerr << command << ": error: " << message << "\nRun '" << command
            << " --help' for the options.\n";
  return deformcd::app::kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "deformcd: deformable-body simulation and parallel collision detection\n"
      "(OpenGL 4.3 compute shaders, with a multithreaded CPU backend)\n"
      "Exit status: 0 done, 1 failed, 2 usage error."};
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

  // CLI11 would say only that an argument was not expected.
  if (argc > 1 && argv[1][0] != '-' && !is_command(app, argv[1])) {
    return usage_error("deformcd", std::string("unknown command '") + argv[1] +
                                       "' (commands: " + command_list(app) + ")");
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    return usage_error(command_name(app), e.what());
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
  } catch (const deformcd::app::UsageError& e) {
    return usage_error(command_name(app), e.what());
  } catch (const deformcd::Error& e) {
    std::cerr << "deformcd: error: " << e.what() << '\n';
    return deformcd::app::kExitFailure;
  } catch (const std::exception& e) {
    std::cerr << "deformcd: unexpected error: " << e.what() << '\n';
    return deformcd::app::kExitFailure;
  }
  return deformcd::app::kExitOk;
}
