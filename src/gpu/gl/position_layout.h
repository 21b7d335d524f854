#pragma once
// Where GlCollision's shaders read each mesh's vertex positions: one float buffer bound at
// gpu::kNodePosition and, per mesh, the word offset and stride of its vertices in it
// (MeshInfo::position_offset, position_stride; vertex_position in
// shaders/collision/surface.glsl). When every mesh's positions lie in the same GL buffer (a
// World's: the simulation's SSBO 0, a vec4 per node), the shaders read that buffer in place and
// nothing is copied. Otherwise each pass gathers them into one buffer of GlCollision's: host
// arrays uploaded, other GL buffers copied on the GPU, each mesh's bytes as they are (its
// stride kept), one region after another. No GL here.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/collision/collision_backend.h"

namespace deformcd::gl {

struct MeshPositionLayout {
  std::uint32_t word_offset = 0;    // vertex 0's x in the bound buffer, in floats
  std::uint32_t word_stride = 0;    // floats from one vertex to the next
  std::uint64_t span_bytes = 0;     // from vertex 0's x to the last vertex's z
  std::uint64_t region_offset = 0;  // gathered: where the mesh's bytes go, in bytes

  bool operator==(const MeshPositionLayout&) const = default;
};

struct PositionLayout {
  // The caller's buffer the shaders read in place, or 0 when the positions are gathered.
  std::uint32_t shared_buffer = 0;
  std::vector<MeshPositionLayout> meshes;  // one per mesh
  std::uint64_t gathered_bytes = 0;        // the gathered buffer's size (0 in place)

  [[nodiscard]] bool in_place() const { return shared_buffer != 0; }
};

// Bytes from vertex 0's x to vertex `vertex_count - 1`'s z: stride x (count - 1) + 12 (0 for
// no vertex). What a source must hold past its offset.
[[nodiscard]] std::uint64_t position_span_bytes(std::uint64_t stride_bytes,
                                                std::uint32_t vertex_count);

// Checks one mesh's source as plan_position_layout does (see there) and returns its span.
[[nodiscard]] std::uint64_t checked_position_span(const collision::PositionSource& source,
                                                  std::uint32_t vertex_count,
                                                  const std::string& label);

// The layout of `sources` (one per mesh, of vertex_counts[m] vertices; labels name the meshes in
// messages). Throws
// Error naming the mesh for a source of the wrong count or kind (kNone: no positions set), a
// null host array, GL buffer 0, an offset or a stride that is not a multiple of 4 or a stride
// below 12 bytes, or a mesh whose last word lies past 2^32 - 1 (the shaders index in uint).
[[nodiscard]] PositionLayout plan_position_layout(
    std::span<const collision::PositionSource> sources,
    std::span<const std::uint32_t> vertex_counts, std::span<const std::string> labels);

}  // namespace deformcd::gl
