#pragma once
// How GlCollision splits the mesh pairs into dispatches, and whether they fit the device. No GL
// here: these run, and are tested, without a context.
//
// A collision dispatch covers a chunk of consecutive mesh pairs along z (one pair per z) and,
// along x and y, the largest row (octree) or face (brute) counts of the chunk's meshes a and b;
// an invocation past its own pair's counts returns. Chunks bound the z extent (the device's
// work-group limit) and, for the octree, the box-mask slots the chunk needs (one per pair).

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "deformcd/gpu_layout.h"

namespace deformcd::gl {

// Consecutive mesh pairs [first, first + count) dispatched together.
struct PairChunk {
  std::uint32_t first = 0;  // index into CollisionData::mesh_pairs
  std::uint32_t count = 0;  // the dispatch's z extent (and mask slots used)
  std::uint32_t max_a = 0;  // largest count of a chunk pair's mesh a: the x extent
  std::uint32_t max_b = 0;  // largest count of a chunk pair's mesh b: the y extent

  bool operator==(const PairChunk&) const = default;
};

// Chunks of at most `chunk_size` (> 0) mesh pairs, in order, covering every pair once; `count`
// is the per-mesh extent, e.g. &gpu::MeshInfo::box_face_count (N', the octree's rows) or
// &gpu::MeshInfo::face_count (N, the baseline's faces).
[[nodiscard]] std::vector<PairChunk> plan_pair_chunks(std::span<const gpu::BodyPair> pairs,
                                                      std::span<const gpu::MeshInfo> meshes,
                                                      std::uint32_t chunk_size,
                                                      std::uint32_t gpu::MeshInfo::*count);

// Work groups of `local_size` covering `invocations` (rounded up).
[[nodiscard]] constexpr std::uint32_t groups_covering(std::uint32_t invocations,
                                                      std::uint32_t local_size) {
  return invocations / local_size + (invocations % local_size != 0 ? 1u : 0u);
}

// Throws GlError naming `shader` and the first chunk whose dispatch (x and y extents covered by
// work groups of local_size, z = count) exceeds `max_groups` on some axis.
void check_chunks_fit(std::string_view shader, std::span<const PairChunk> chunks,
                      const std::array<std::uint32_t, 3>& local_size,
                      const std::array<std::uint32_t, 3>& max_groups);

}  // namespace deformcd::gl
