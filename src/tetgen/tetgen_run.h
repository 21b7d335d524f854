#pragma once
// The TetGen call itself, meant to run inside an isolated child process (isolated_run.h), and
// the transport of its result back to the parent as raw bytes.

#include <string>

#include "deformcd/mesh.h"

namespace deformcd::detail {

/// Child status when TetGen's diagnosis (-d) finds intersecting faces.
inline constexpr int kSelfIntersecting = 103;
/// Child status when TetGen rejects the switches.
inline constexpr int kBadSwitches = 110;

/// Runs TetGen's self-intersection diagnosis, then TetGen with `switches` (which must include
/// 'z' for zero-based output). Returns 0 with the serialized mesh in `output`; kSelfIntersecting
/// with the number of intersecting faces in `output`; or TetGen's failure code.
int run_tetgen(const SurfaceMesh& surface, const std::string& switches, std::string& output);

/// Rebuilds the mesh run_tetgen serialized. Throws deformcd::Error if the bytes are truncated.
[[nodiscard]] TetMesh deserialize_tetgen_output(const std::string& bytes);

/// What TetGen's exit codes (terminatetetgen) mean, in words.
[[nodiscard]] std::string explain_tetgen_failure(int code);

}  // namespace deformcd::detail
