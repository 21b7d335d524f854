#include "gpu/gl/compute_program.h"

#include <epoxy/gl.h>

#include <string>

#include "deformcd/error.h"
#include "gpu/gl/gl_check.h"

namespace deformcd::gl {

ComputeProgram::ComputeProgram(std::string_view name, const ShaderLibrary& library)
    : Program({{GL_COMPUTE_SHADER, name}}, library, "compute shader '" + std::string(name) + "'",
              "compute shader '" + std::string(name) + "' has"),
      shader_name_(name) {
  GLint size[3] = {0, 0, 0};
  DEFORMCD_GL_CHECK(glGetProgramiv(this->name(), GL_COMPUTE_WORK_GROUP_SIZE, size));
  for (GLuint axis = 0; axis < 3; ++axis) {
    work_group_size_[axis] = static_cast<std::uint32_t>(size[axis]);
    GLint max_count = 0;
    DEFORMCD_GL_CHECK(glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, axis, &max_count));
    max_work_group_count_[axis] = static_cast<std::uint32_t>(max_count);
  }
}

void ComputeProgram::dispatch(std::uint32_t groups_x, std::uint32_t groups_y,
                              std::uint32_t groups_z) const {
  const std::array<std::uint32_t, 3> groups = {groups_x, groups_y, groups_z};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (groups[axis] > max_work_group_count_[axis]) {
      throw GlError("dispatching '" + shader_name_ + "': " + std::to_string(groups[axis]) +
                    " work groups along " + "xyz"[axis] + " exceed the device's maximum of " +
                    std::to_string(max_work_group_count_[axis]));
    }
  }
  use();
  DEFORMCD_GL_CHECK(glDispatchCompute(groups_x, groups_y, groups_z));
}

void ComputeProgram::dispatch_covering(std::uint32_t invocations) const {
  const std::uint32_t local = work_group_size_[0];
  // Written to avoid overflowing near 2^32 invocations.
  const std::uint32_t groups = invocations / local + (invocations % local != 0 ? 1u : 0u);
  if (groups > 0) dispatch(groups);
}

void ComputeProgram::dispatch_indirect(std::uint32_t args, std::uint32_t word) const {
  use();
  DEFORMCD_GL_CHECK(glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, args));
  DEFORMCD_GL_CHECK(glDispatchComputeIndirect(static_cast<GLintptr>(word * sizeof(std::uint32_t))));
}

void storage_barrier() {
  DEFORMCD_GL_CHECK(glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT));
}

void command_barrier() {
  DEFORMCD_GL_CHECK(glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT));
}

void memory_barrier(std::uint32_t barrier_bits) {
  DEFORMCD_GL_CHECK(glMemoryBarrier(barrier_bits));
}

}  // namespace deformcd::gl
