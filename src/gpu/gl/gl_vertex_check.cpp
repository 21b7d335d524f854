#include "gpu/gl/gl_vertex_check.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <vector>

#include "deformcd/gpu_layout.h"
#include "gpu/gl/buffer_from.h"
#include "gpu/gl/collision_dispatch_plan.h"
#include "gpu/gl/collision_work_buffers.h"
#include "gpu/gl/gl_check.h"

namespace deformcd::gl {

namespace {

constexpr std::uint32_t kNoVertex = 0xFFFFFFFFu;

}  // namespace

VertexCheck::VertexCheck(std::uint32_t max_groups_x)
    : program_("collision/vertex_check.comp"), max_groups_x_(max_groups_x) {}

bool VertexCheck::find(const PositionStaging& staging, std::uint32_t& mesh, std::uint32_t& vertex) {
  using Kind = collision::PositionSource::Kind;
  const std::vector<collision::PositionSource>& sources = staging.sources();
  const std::size_t meshes = sources.size();
  std::vector<std::uint32_t> checked;
  for (std::uint32_t m = 0; m < meshes; ++m) {
    if (sources[m].kind == Kind::kGl && sources[m].vertex_count > 0) checked.push_back(m);
  }
  if (checked.empty()) return false;
  if (!first_bad_ || first_bad_->size() < meshes) {
    first_bad_ =
        allocate<std::uint32_t>(meshes, {"GL collision", "Non-Finite Vertex", kNonFiniteBinding});
  }
  DEFORMCD_GL_CHECK(glBindBuffer(GL_SHADER_STORAGE_BUFFER, first_bad_->name()));
  DEFORMCD_GL_CHECK(glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER,
                                      GL_UNSIGNED_INT, &kNoVertex));
  first_bad_->bind(kNonFiniteBinding);
  for (std::uint32_t m : checked) {
    staging.bind_gl_source(m, gpu::kNodePosition);
    const collision::PositionSource& s = sources[m];
    const std::uint32_t count = s.vertex_count;
    // checked_position_span (in bind_gl_source) made the words fit uint.
    program_.set_uniform("u_mesh", m);
    program_.set_uniform("u_vertex_count", count);
    program_.set_uniform("u_offset", static_cast<std::uint32_t>(s.offset_bytes / sizeof(float)));
    program_.set_uniform("u_stride", static_cast<std::uint32_t>(s.stride_bytes / sizeof(float)));
    // The shader strides over what one dispatch does not cover.
    program_.dispatch(
        std::min(groups_covering(count, program_.work_group_size()[0]), max_groups_x_));
  }
  // One read (waits for the dispatches): the lowest mesh with a bad vertex, its lowest vertex.
  const std::vector<std::uint32_t> first = first_bad_->download(0, meshes);
  for (std::uint32_t m : checked) {
    if (first[m] == kNoVertex) continue;
    mesh = m;
    vertex = first[m];
    return true;
  }
  return false;
}

}  // namespace deformcd::gl
