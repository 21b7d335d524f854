#pragma once
// GlCollision::find_non_finite: the first vertex with a NaN or infinite coordinate among the
// meshes whose positions are in GL buffers, found on the GPU (shaders/collision/
// vertex_check.comp, one dispatch per such mesh) and read back in one read of one uint per mesh.
// Meshes with host positions are skipped: the Detector checks host arrays itself, where they
// are, without an upload. Nothing the last pass left is touched: the check has its own result
// buffer and binding (34), and the next pass rebinds SSBO 0.

#include <cstdint>
#include <optional>

#include "deformcd/gl/ssbo.h"
#include "gpu/gl/compute_program.h"
#include "gpu/gl/gl_position_staging.h"

namespace deformcd::gl {

class VertexCheck {
 public:
  // Compiles the shader (GlError if that fails); `max_groups_x` is the device's dispatch limit.
  explicit VertexCheck(std::uint32_t max_groups_x);

  // The lowest (mesh, vertex), in that order, with a non-finite coordinate among the GL-sourced
  // meshes of `staging`. Throws as PositionStaging::stage for a GL buffer that no longer holds
  // its mesh.
  [[nodiscard]] bool find(const PositionStaging& staging, std::uint32_t& mesh,
                          std::uint32_t& vertex);

 private:
  ComputeProgram program_;
  std::uint32_t max_groups_x_ = 0;
  std::optional<Ssbo<std::uint32_t>> first_bad_;  // per mesh, SSBO 34
};

}  // namespace deformcd::gl
