#include "gpu/gl/gl_position_staging.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <string>
#include <utility>

#include "deformcd/error.h"
#include "gpu/gl/buffer_from.h"
#include "gpu/gl/gl_check.h"

namespace deformcd::gl {

namespace {

using Kind = collision::PositionSource::Kind;
using std::to_string;

// Vertex i's x, y, z at words[i * stride_words ...].
std::vector<glm::vec3> unpack(const float* words, std::uint64_t stride_words, std::uint32_t count) {
  std::vector<glm::vec3> out(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const float* w = words + i * stride_words;
    out[i] = glm::vec3(w[0], w[1], w[2]);
  }
  return out;
}

// The vertices at byte `offset` of GL buffer `buffer`, read back (waits for the GPU).
std::vector<glm::vec3> read_gl(std::uint32_t buffer, std::uint64_t offset,
                               std::uint64_t stride_bytes, std::uint32_t count) {
  const std::uint64_t span = position_span_bytes(stride_bytes, count);
  if (span == 0) return {};
  std::vector<float> words(span / sizeof(float));
  // Shader writes (a simulation's, our gathering copies) land before the read.
  DEFORMCD_GL_CHECK(glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT));
  DEFORMCD_GL_CHECK(glBindBuffer(GL_COPY_READ_BUFFER, buffer));
  DEFORMCD_GL_CHECK(glGetBufferSubData(GL_COPY_READ_BUFFER, static_cast<GLintptr>(offset),
                                       static_cast<GLsizeiptr>(span), words.data()));
  return unpack(words.data(), stride_bytes / sizeof(float), count);
}

// The size in bytes of buffer object `buffer`, or nothing when the name is not one.
std::optional<std::uint64_t> gl_buffer_size(std::uint32_t buffer) {
  if (buffer == 0 || glIsBuffer(buffer) != GL_TRUE) return std::nullopt;
  GLint64 bytes = 0;
  DEFORMCD_GL_CHECK(glBindBuffer(GL_COPY_READ_BUFFER, buffer));
  DEFORMCD_GL_CHECK(glGetBufferParameteri64v(GL_COPY_READ_BUFFER, GL_BUFFER_SIZE, &bytes));
  return static_cast<std::uint64_t>(bytes);
}

}  // namespace

void PositionStaging::set_labels(std::vector<std::string> labels) {
  labels_ = std::move(labels);
}

void PositionStaging::set_sources(std::vector<collision::PositionSource> sources) {
  for (std::size_t m = 0; m < sources.size(); ++m) {
    if (sources[m].kind != Kind::kNone) (void)checked_source(sources[m], m);
  }
  sources_ = std::move(sources);
  sources_changed_ = true;
}

bool PositionStaging::stage(const std::vector<gpu::MeshInfo>& meshes) {
  if (sources_.size() != meshes.size()) {
    throw Error("GL collision: positions set for " + to_string(sources_.size()) +
                " meshes, but there are " + to_string(meshes.size()));
  }
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const collision::PositionSource& s = sources_[m];
    if (s.kind != Kind::kNone && s.vertex_count != meshes[m].vertex_count) {
      throw Error("GL collision: " + label(m) + "'s positions are set for " +
                  to_string(s.vertex_count) + " vertices, but the mesh has " +
                  to_string(meshes[m].vertex_count));
    }
  }
  // The layout follows from the sources alone: planned again only when they changed.
  const bool replan = !layout_ || sources_changed_;
  PositionLayout layout = replan ? plan(meshes) : *layout_;
  // Every GL source is checked every pass: the caller may have reallocated a buffer since.
  std::uint64_t shared_bytes = 0;
  for (std::size_t m = 0; m < sources_.size(); ++m) {
    if (sources_[m].kind == Kind::kGl) shared_bytes = checked_source(sources_[m], m);
  }
  if (layout.in_place()) {
    shared_bytes_ = std::min(shared_bytes, limits_.max_block_bytes);
  } else {
    gather(layout);
  }
  const bool words_changed = !layout_ || layout_->meshes != layout.meshes;
  layout_ = std::move(layout);
  sources_changed_ = false;
  return words_changed;
}

PositionLayout PositionStaging::plan(const std::vector<gpu::MeshInfo>& meshes) const {
  std::vector<std::uint32_t> counts;
  std::vector<std::string> labels;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    counts.push_back(meshes[m].vertex_count);
    labels.push_back(label(m));
  }
  return plan_position_layout(sources_, counts, labels);
}

void PositionStaging::gather(const PositionLayout& layout) {
  if (layout.gathered_bytes > limits_.max_gathered_bytes) {
    throw GlError("GL collision: gathering the meshes' positions into one buffer (SSBO 0) takes " +
                  to_string(layout.gathered_bytes) + " bytes, more than " + limits_.limit_name +
                  " (" + to_string(limits_.max_gathered_bytes) +
                  " bytes); positions all in one GL buffer are read in place");
  }
  // Kept from pass to pass; a binding of zero bytes is an error on some drivers.
  const std::uint64_t bytes = std::max<std::uint64_t>(layout.gathered_bytes, sizeof(float));
  if (!gathered_ || gathered_->size_bytes() < bytes) {
    // The old buffer goes only once the new one is had.
    try {
      gathered_ = BufferObject(bytes);
    } catch (const GlError& e) {
      throw allocation_error({"GL collision", "Gathered Positions", gpu::kNodePosition}, bytes, 1,
                             e);
    }
  }
  // Shader writes to the callers' buffers land before the copies read them.
  DEFORMCD_GL_CHECK(glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT));
  for (std::size_t m = 0; m < sources_.size(); ++m) {
    const collision::PositionSource& s = sources_[m];
    const MeshPositionLayout& to = layout.meshes[m];
    if (to.span_bytes == 0) continue;
    if (s.kind == Kind::kHost) {
      gathered_->upload(s.host, to.span_bytes, to.region_offset);
      continue;
    }
    DEFORMCD_GL_CHECK(glBindBuffer(GL_COPY_READ_BUFFER, s.gl_buffer));
    DEFORMCD_GL_CHECK(glBindBuffer(GL_COPY_WRITE_BUFFER, gathered_->name()));
    DEFORMCD_GL_CHECK(glCopyBufferSubData(
        GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, static_cast<GLintptr>(s.offset_bytes),
        static_cast<GLintptr>(to.region_offset), static_cast<GLsizeiptr>(to.span_bytes)));
  }
}

void PositionStaging::bind() const {
  if (layout_->in_place()) {
    DEFORMCD_GL_CHECK(glBindBufferRange(GL_SHADER_STORAGE_BUFFER, gpu::kNodePosition,
                                        layout_->shared_buffer, 0,
                                        static_cast<GLsizeiptr>(shared_bytes_)));
  } else {
    gathered_->bind_storage(gpu::kNodePosition);
  }
}

std::vector<glm::vec3> PositionStaging::read_source(std::uint32_t mesh) const {
  if (mesh >= sources_.size() || sources_[mesh].kind == Kind::kNone) {
    throw Error("GL collision: " + label(mesh) + " has no positions set");
  }
  const collision::PositionSource& s = sources_[mesh];
  (void)checked_source(s, mesh);
  if (s.kind == Kind::kHost) return unpack(s.host, s.stride_bytes / sizeof(float), s.vertex_count);
  return read_gl(s.gl_buffer, s.offset_bytes, s.stride_bytes, s.vertex_count);
}

std::vector<glm::vec3> PositionStaging::read_staged(std::uint32_t mesh) const {
  const MeshPositionLayout& at = layout_->meshes[mesh];
  const std::uint32_t buffer = layout_->in_place() ? layout_->shared_buffer : gathered_->name();
  return read_gl(buffer, std::uint64_t{at.word_offset} * sizeof(float),
                 std::uint64_t{at.word_stride} * sizeof(float), sources_[mesh].vertex_count);
}

void PositionStaging::bind_gl_source(std::uint32_t mesh, std::uint32_t binding) const {
  const collision::PositionSource& s = sources_[mesh];
  const std::uint64_t bytes = std::min(checked_source(s, mesh), limits_.max_block_bytes);
  DEFORMCD_GL_CHECK(glBindBufferRange(GL_SHADER_STORAGE_BUFFER, binding, s.gl_buffer, 0,
                                      static_cast<GLsizeiptr>(bytes)));
}

std::string PositionStaging::label(std::size_t mesh) const {
  return mesh < labels_.size() && !labels_[mesh].empty() ? labels_[mesh]
                                                         : "mesh " + to_string(mesh);
}

std::uint64_t PositionStaging::checked_source(const collision::PositionSource& s,
                                              std::size_t mesh) const {
  const std::uint64_t span = checked_position_span(s, s.vertex_count, label(mesh));
  if (s.kind != Kind::kGl) return 0;
  const std::string what =
      "GL collision: " + label(mesh) + "'s positions in GL buffer " + to_string(s.gl_buffer) + ": ";
  const std::optional<std::uint64_t> size = gl_buffer_size(s.gl_buffer);
  if (!size) throw Error(what + "not a buffer (deleted, or never created)");
  // checked_position_span bounds offset + span far below 2^64.
  const std::uint64_t end = s.offset_bytes + span;
  if (end > *size) {
    throw Error(what + "the buffer holds " + to_string(*size) + " bytes, fewer than the " +
                to_string(end) + " its " + to_string(s.vertex_count) + " vertices need (offset " +
                to_string(s.offset_bytes) + ", stride " + to_string(s.stride_bytes) +
                "); was it reallocated?");
  }
  if (end > limits_.max_block_bytes) {
    throw GlError(what + "its vertices end at byte " + to_string(end) + ", past the " +
                  to_string(limits_.max_block_bytes) +
                  " bytes a shader may read of a buffer (GL_MAX_SHADER_STORAGE_BLOCK_SIZE)");
  }
  return *size;
}

}  // namespace deformcd::gl
