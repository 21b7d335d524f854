#include "gpu/gl/collision_dispatch_plan.h"

#include <algorithm>
#include <string>

#include "deformcd/error.h"

namespace deformcd::gl {

std::vector<PairChunk> plan_pair_chunks(std::span<const gpu::BodyPair> pairs,
                                        std::span<const gpu::MeshInfo> meshes,
                                        std::uint32_t chunk_size,
                                        std::uint32_t gpu::MeshInfo::*count) {
  if (chunk_size == 0) throw Error("plan_pair_chunks: the chunk size must be positive");
  std::vector<PairChunk> chunks;
  const auto pair_count = static_cast<std::uint32_t>(pairs.size());
  for (std::uint32_t first = 0; first < pair_count;
       first += std::min(chunk_size, pair_count - first)) {
    PairChunk chunk{first, std::min(chunk_size, pair_count - first), 0, 0};
    for (std::uint32_t p = first; p < first + chunk.count; ++p) {
      chunk.max_a = std::max(chunk.max_a, meshes[pairs[p].a].*count);
      chunk.max_b = std::max(chunk.max_b, meshes[pairs[p].b].*count);
    }
    chunks.push_back(chunk);
  }
  return chunks;
}

void check_chunks_fit(std::string_view shader, std::span<const PairChunk> chunks,
                      const std::array<std::uint32_t, 3>& local_size,
                      const std::array<std::uint32_t, 3>& max_groups) {
  for (const PairChunk& chunk : chunks) {
    const std::array<std::uint32_t, 3> groups = {groups_covering(chunk.max_a, local_size[0]),
                                                 groups_covering(chunk.max_b, local_size[1]),
                                                 chunk.count};
    for (std::size_t axis = 0; axis < 3; ++axis) {
      if (groups[axis] <= max_groups[axis]) continue;
      throw GlError("GL collision: '" + std::string(shader) + "' would need " +
                    std::to_string(groups[axis]) + " work groups along " + "xyz"[axis] +
                    " for mesh pairs " + std::to_string(chunk.first) + " to " +
                    std::to_string(chunk.first + chunk.count - 1) + " (extents " +
                    std::to_string(chunk.max_a) + " x " + std::to_string(chunk.max_b) + " x " +
                    std::to_string(chunk.count) +
                    "), more than the device's GL_MAX_COMPUTE_WORK_GROUP_COUNT of " +
                    std::to_string(max_groups[axis]));
    }
  }
}

}  // namespace deformcd::gl
