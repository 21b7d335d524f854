#pragma once
// The subcommands of the deformcd tool. Each registers its options on the CLI11 app and returns
// the exit status when run. Errors are thrown (deformcd::Error) and reported by main().

#include <CLI/CLI.hpp>

#include <functional>

namespace deformcd::app {

using Command = std::function<int()>;

/// `deformcd info MODEL [--json] [--merge-edges]` and `deformcd info --gpu [--json]`.
Command add_info_command(CLI::App& app);

/// `deformcd tetra IN -o PREFIX [--quality Q] [--max-volume V] [--preserve-surface]`.
Command add_tetra_command(CLI::App& app);

/// `deformcd run SCENE [--frames N] [--backend auto|gl|cpu] [--threads T] [--broadphase METHOD]
/// [--contacts FILE] [--positions FILE [--every-frame]]`.
Command add_run_command(CLI::App& app);

/// `deformcd collide A.off B.stl ... [--self] [--backend gl|cpu|auto] [--broadphase METHOD]
/// [--threads T] [--json FILE]`.
Command add_collide_command(CLI::App& app);

/// `deformcd bench SCENE... [--frames N] [--backend gl,cpu] [--methods all|M1,M2,...]
/// [--repeat R] [--threads T] [--json FILE] [--csv FILE] [--plot FILE.png]`.
Command add_bench_command(CLI::App& app);

#ifdef DEFORMCD_HAS_RENDER
/// `deformcd render SCENE (--at K1,K2,... | --every-frame | --video FILE) -o DIR [--frames N]
/// [--size WxH] [--broadphase METHOD] [--shaded] [--backend gl]`.
Command add_render_command(CLI::App& app);

/// `deformcd view SCENE [--frames N] [--broadphase METHOD] [--quit-after K] [--screenshot FILE]`.
Command add_view_command(CLI::App& app);
#endif

}  // namespace deformcd::app
