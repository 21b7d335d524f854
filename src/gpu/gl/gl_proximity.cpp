#include "gl_proximity.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <string>

#include "buffer_from.h"
#include "deformcd/error.h"
#include "gl_check.h"

namespace deformcd::gl {

namespace {

static_assert(sizeof(collision::ProximityCandidate) == 32,
              "ProximityCandidate is read back as the GLSL struct (proximity.glsl)");

// Item p's first work item: mesh pair p's mesh a's faces follow the earlier pairs'.
std::vector<std::uint32_t> pair_first_items(const collision::CollisionData& data) {
  std::vector<std::uint32_t> first = {0u};
  for (const gpu::BodyPair& pair : data.mesh_pairs)
    first.push_back(first.back() + data.meshes[pair.a].face_count);
  return first;
}

template <class T>
Ssbo<T> at_least_one(const std::vector<T>& data) {
  Ssbo<T> buffer(std::max<std::size_t>(data.size(), 1));
  buffer.upload(std::span<const T>(data));
  return buffer;
}

void bind_name(std::uint32_t binding, std::uint32_t buffer) {
  DEFORMCD_GL_CHECK(glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer));
}

}  // namespace

GlProximity::GlProximity(Context& context, const collision::CollisionData& data)
    : GlProximity(query_device_info(context), data) {}

GlProximity::GlProximity(const DeviceInfo& device, const collision::CollisionData& data)
    : max_buffer_bytes_(device.max_ssbo_block_bytes),
      mesh_count_(static_cast<std::uint32_t>(data.mesh_count())),
      pair_count_(static_cast<std::uint32_t>(data.mesh_pairs.size())),
      item_count_(pair_first_items(data).back()),
      count_("proximity/proximity_count.comp"),
      scan_("proximity/proximity_scan.comp"),
      emit_("proximity/proximity_emit.comp"),
      owners_(at_least_one(collision::primitive_owners(data.faces))),
      mesh_pairs_(at_least_one(data.mesh_pairs)),
      pair_first_(at_least_one(pair_first_items(data))),
      reach_(std::max<std::size_t>(data.mesh_count(), 1)),
      counts_(std::max<std::uint32_t>(item_count_, 1u)),
      offsets_(std::size_t{item_count_} + 1u) {
  for (ComputeProgram* p : {&count_, &emit_}) {
    p->set_uniform("u_pair_count", pair_count_);
    p->set_uniform("u_item_count", item_count_);
  }
  scan_.set_uniform("u_item_count", item_count_);
  const std::uint64_t most =
      std::uint64_t{device.max_work_group_count[0]} * count_.work_group_size()[0];
  if (item_count_ > most) {
    throw GlError("GL proximity: " + std::to_string(item_count_) +
                  " work items (faces of the mesh pairs' first meshes) exceed one dispatch (" +
                  std::to_string(most) + ")");
  }
}

std::vector<collision::ProximityCandidate> GlProximity::find(const ProximitySources& sources,
                                                             std::span<const float> reach,
                                                             std::span<const glm::vec3> drift) {
  check_reach(reach, drift);  // before anything is rebound
  bind_name(gpu::kNodePosition, sources.positions);
  bind_name(gpu::kFaceInfo, sources.faces);
  bind_name(gpu::kMeshInfo, sources.meshes);
  bind_name(gpu::kBvhNode, sources.bvh_nodes);
  bind_name(gpu::kBvhBox, sources.bvh_boxes);
  bind_name(gpu::kBodyBvh, sources.mesh_bvhs);
  return find_bound(reach, drift);
}

void GlProximity::check_reach(std::span<const float> reach,
                              std::span<const glm::vec3> drift) const {
  if (reach.size() != mesh_count_ || drift.size() != mesh_count_) {
    throw Error("GlProximity::find takes one reach and one drift per mesh: " +
                std::to_string(mesh_count_) + " expected, " + std::to_string(reach.size()) +
                " and " + std::to_string(drift.size()) + " given");
  }
}

std::vector<collision::ProximityCandidate> GlProximity::find_bound(
    std::span<const float> reach, std::span<const glm::vec3> drift) {
  check_reach(reach, drift);
  if (item_count_ == 0) return {};
  std::vector<glm::vec4> packed(reach.size());
  for (std::size_t m = 0; m < reach.size(); ++m)
    packed[m] = glm::vec4(drift[m], reach[m]);
  reach_.upload(std::span<const glm::vec4>(packed));
  mesh_pairs_.bind(gpu::kBodyPair);
  owners_.bind(kProximityOwnersBinding);
  reach_.bind(kProximityReachBinding);
  pair_first_.bind(kProximityPairFirstBinding);
  counts_.bind(kProximityCountsBinding);
  offsets_.bind(kProximityOffsetsBinding);

  count_.dispatch_covering(item_count_);
  storage_barrier();  // the scan reads the counts
  scan_.dispatch(1);
  // The total sizes the output: the one wait inside a search.
  const std::uint32_t total = offsets_.download(item_count_, 1)[0];
  if (total == 0) return {};
  if (!candidates_ || candidates_->size() < total) {
    // 1.5 x the need, within the limit: a list growing over frames is rarely reallocated.
    const std::uint64_t most = max_buffer_bytes_ / sizeof(collision::ProximityCandidate);
    if (total > most) {
      throw GlError("GL proximity: " + std::to_string(total) + " candidates (" +
                    std::to_string(std::uint64_t{total} * sizeof(collision::ProximityCandidate)) +
                    " bytes) exceed the device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE (" +
                    std::to_string(max_buffer_bytes_) + " bytes); use smaller reaches");
    }
    candidates_ = allocate<collision::ProximityCandidate>(
        std::min<std::uint64_t>(std::uint64_t{total} + total / 2u, most),
        {"GL proximity", "Proximity Candidates", kProximityCandidatesBinding});
  }
  candidates_->bind(kProximityCandidatesBinding);
  storage_barrier();  // the emit pass reads the offsets
  emit_.dispatch_covering(item_count_);
  return candidates_->download(0, total);
}

}  // namespace deformcd::gl
