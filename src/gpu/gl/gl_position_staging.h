#pragma once
// GlCollision's vertex positions on the GPU (the layout: position_layout.h). set_sources()
// checks each source where it is (a GL buffer must exist and hold its mesh's vertices); before
// each pass, stage() checks the GL buffers again (the caller may have deleted one, or
// reallocated it smaller, since) and, unless every mesh is in one GL buffer read in place,
// gathers the positions into a buffer of its own: host arrays with glBufferSubData, other GL
// buffers with glCopyBufferSubData (on the GPU). It also reads a mesh's positions back for the
// host (a detector's hierarchies, BVH rebuilds). A context must be current for every call.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/collision/collision_backend.h"
#include "deformcd/gl/ssbo.h"
#include "deformcd/gpu_layout.h"
#include "gpu/gl/position_layout.h"

namespace deformcd::gl {

struct StagingLimits {
  // What a shader may read of a buffer (GL_MAX_SHADER_STORAGE_BLOCK_SIZE): a caller's buffer is
  // bound up to it, and a mesh whose positions end past it is refused.
  std::uint64_t max_block_bytes = 0;
  // The largest gathered buffer, and the name of that limit in messages.
  std::uint64_t max_gathered_bytes = 0;
  std::string limit_name;
};

class PositionStaging {
 public:
  explicit PositionStaging(StagingLimits limits) : limits_(std::move(limits)) {}

  // Labels of the meshes for messages ("mesh 1 ('cloth')"); "mesh m" where none is given.
  void set_labels(std::vector<std::string> labels);
  // Where each mesh's positions are (with its vertex count), from the next stage() on. A kNone
  // source is a mesh whose positions are not set yet. Throws Error naming the mesh for a
  // malformed source or a GL buffer that does not hold the mesh's vertices (GlError when they
  // end past what a shader may read); nothing changes then.
  void set_sources(std::vector<collision::PositionSource> sources);
  [[nodiscard]] const std::vector<collision::PositionSource>& sources() const { return sources_; }

  // Makes every mesh's current positions readable where layout() says, for the next pass over
  // `meshes`. Throws Error naming the mesh for a missing source or one of another vertex count
  // than its mesh, or (and the buffer) a GL buffer that no longer holds the mesh; GlError when
  // the gathered buffer would exceed the limit. Returns whether the per-mesh words
  // (MeshInfo::position_offset, position_stride) changed since the last stage().
  bool stage(const std::vector<gpu::MeshInfo>& meshes);
  // Forgets the last stage(): the next one reports a change (a new mesh buffer).
  void restart() { layout_.reset(); }
  // Whether a stage() succeeded since restart(); then layout() is its layout.
  [[nodiscard]] bool staged() const { return layout_.has_value(); }
  [[nodiscard]] const PositionLayout& layout() const { return *layout_; }
  // Binds the last stage()'s buffer at gpu::kNodePosition.
  void bind() const;

  // Mesh `mesh`'s current positions, from its source (a GL buffer is checked first).
  [[nodiscard]] std::vector<glm::vec3> read_source(std::uint32_t mesh) const;
  // The positions of mesh `mesh` the last stage() made readable: the last pass's.
  [[nodiscard]] std::vector<glm::vec3> read_staged(std::uint32_t mesh) const;
  // Checks mesh `mesh`'s GL source as stage() does and binds its buffer at `binding`.
  void bind_gl_source(std::uint32_t mesh, std::uint32_t binding) const;

 private:
  [[nodiscard]] std::string label(std::size_t mesh) const;
  // Checks source `s` of mesh `mesh`; for a GL source, that its buffer holds the vertices
  // within what a shader may read, returning the buffer's size.
  std::uint64_t checked_source(const collision::PositionSource& s, std::size_t mesh) const;
  [[nodiscard]] PositionLayout plan(const std::vector<gpu::MeshInfo>& meshes) const;
  void gather(const PositionLayout& layout);

  StagingLimits limits_;
  std::vector<std::string> labels_;
  std::vector<collision::PositionSource> sources_;
  bool sources_changed_ = true;  // since the last stage(): the layout is planned again
  std::optional<PositionLayout> layout_;
  std::uint64_t shared_bytes_ = 0;  // the shared buffer's bound range (in place)
  std::optional<BufferObject> gathered_;
};

}  // namespace deformcd::gl
