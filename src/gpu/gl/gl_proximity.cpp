#include "gpu/gl/gl_proximity.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <string>

#include "deformcd/error.h"
#include "gpu/gl/buffer_from.h"
#include "gpu/gl/gl_check.h"

namespace deformcd::gl {

namespace {

static_assert(sizeof(collision::ProximityCandidate) == 32,
              "ProximityCandidate is read back as the GLSL struct (proximity.glsl)");

// Every mesh's tree has 2 x faces - 1 nodes (collision::build_hierarchies; rebuilds keep it).
std::uint32_t node_total(const collision::CollisionData& data) {
  std::uint32_t total = 0;
  for (const gpu::MeshInfo& mesh : data.meshes)
    total += 2u * mesh.face_count - 1u;
  return total;
}

// Each searched pair's first work item (`pairs`: indices into `all`), then their total: a
// pair's mesh a's faces follow the earlier pairs'.
std::vector<std::uint32_t> pair_first_items(const std::vector<gpu::BodyPair>& all,
                                            const std::vector<gpu::MeshInfo>& meshes,
                                            std::span<const std::uint32_t> pairs) {
  std::vector<std::uint32_t> first = {0u};
  for (const std::uint32_t p : pairs)
    first.push_back(first.back() + meshes[all[p].a].face_count);
  return first;
}

template <class T>
Ssbo<T> at_least_one(const std::vector<T>& data) {
  Ssbo<T> buffer(std::max<std::size_t>(data.size(), 1));
  buffer.upload(std::span<const T>(data));
  return buffer;
}

}  // namespace

GlProximity::GlProximity(Context& context, const collision::CollisionData& data)
    : GlProximity(query_device_info(context), data) {}

GlProximity::GlProximity(const DeviceInfo& device, const collision::CollisionData& data)
    : GlProximity(device, data, collision::vertex_firsts(data),
                  pair_first_items(data.mesh_pairs, data.meshes,
                                   collision::searched_mesh_pairs(data, {}))) {}

GlProximity::GlProximity(const DeviceInfo& device, const collision::CollisionData& data,
                         const std::vector<std::uint32_t>& vertex_first,
                         const std::vector<std::uint32_t>& pair_first)
    : max_buffer_bytes_(device.max_ssbo_block_bytes),
      vertex_count_(vertex_first.back()),
      node_count_(node_total(data)),
      all_pairs_(data.mesh_pairs),
      meshes_(data.meshes),
      searched_(collision::searched_mesh_pairs(data, {})),
      pair_count_(static_cast<std::uint32_t>(data.mesh_pairs.size())),
      item_count_(pair_first.back()),
      refit_("proximity/proximity_refit.comp"),
      refit_level_("proximity/proximity_refit_level.comp"),
      count_("proximity/proximity_count.comp"),
      scan_("proximity/proximity_scan.comp"),
      emit_("proximity/proximity_emit.comp"),
      owners_(at_least_one(collision::primitive_owners(data.faces))),
      mesh_pairs_(at_least_one(data.mesh_pairs)),
      pair_first_(at_least_one(pair_first)),
      vertex_first_(vertex_first),
      motion_(std::max<std::uint32_t>(vertex_count_, 1u)),
      boxes_(std::max<std::uint32_t>(node_count_, 1u)),
      counts_(std::max<std::uint32_t>(item_count_, 1u)),
      offsets_(std::size_t{item_count_} + 1u) {
  set_item_uniforms();
  refit_.set_uniform("u_node_count", node_count_);
  const std::uint64_t most =
      std::uint64_t{device.max_work_group_count[0]} * count_.work_group_size()[0];
  if (item_count_ > most || node_count_ > most) {
    throw GlError("GL proximity: " + std::to_string(item_count_) +
                  " work items (faces of the mesh pairs' first meshes) or " +
                  std::to_string(node_count_) + " BVH nodes exceed one dispatch (" +
                  std::to_string(most) + ")");
  }
}

void GlProximity::set_item_uniforms() {
  for (ComputeProgram* p : {&count_, &emit_}) {
    p->set_uniform("u_pair_count", pair_count_);
    p->set_uniform("u_item_count", item_count_);
  }
  scan_.set_uniform("u_item_count", item_count_);
}

void GlProximity::search_pairs(std::span<const std::uint32_t> mesh_pairs) {
  if (std::equal(mesh_pairs.begin(), mesh_pairs.end(), searched_.begin(), searched_.end())) return;
  // A subset of the pairs uploaded at construction: the buffers hold them all.
  std::vector<gpu::BodyPair> pairs;
  pairs.reserve(mesh_pairs.size());
  for (const std::uint32_t p : mesh_pairs)
    pairs.push_back(all_pairs_[p]);
  const std::vector<std::uint32_t> first = pair_first_items(all_pairs_, meshes_, mesh_pairs);
  if (!pairs.empty()) mesh_pairs_.upload(std::span<const gpu::BodyPair>(pairs));
  pair_first_.upload(std::span<const std::uint32_t>(first));
  searched_.assign(mesh_pairs.begin(), mesh_pairs.end());
  pair_count_ = static_cast<std::uint32_t>(pairs.size());
  item_count_ = first.back();
  set_item_uniforms();
}

std::vector<collision::ProximityCandidate> GlProximity::find(
    const ProximitySources& sources, std::span<const float> reach,
    std::span<const glm::vec3> motion, std::span<const std::uint32_t> mesh_pairs) {
  check_lists(reach, motion, mesh_pairs);  // before anything is rebound
  bind_storage_buffer(gpu::kNodePosition, sources.positions);
  bind_storage_buffer(gpu::kFaceInfo, sources.faces);
  bind_storage_buffer(gpu::kMeshInfo, sources.meshes);
  bind_storage_buffer(gpu::kBvhNode, sources.bvh_nodes);
  bind_storage_buffer(gpu::kBodyBvh, sources.mesh_bvhs);
  return find_bound(sources.refit, reach, motion, mesh_pairs);
}

void GlProximity::check_lists(std::span<const float> reach, std::span<const glm::vec3> motion,
                              std::span<const std::uint32_t> mesh_pairs) const {
  if (reach.size() != vertex_count_ || (!motion.empty() && motion.size() != vertex_count_)) {
    throw Error(
        "GlProximity::find takes one reach and one motion (or none) per vertex of every "
        "mesh: " +
        std::to_string(vertex_count_) + " expected, " + std::to_string(reach.size()) +
        " reaches and " + std::to_string(motion.size()) + " motions given");
  }
  for (std::size_t i = 0; i < mesh_pairs.size(); ++i) {
    if (mesh_pairs[i] >= all_pairs_.size() || (i > 0 && mesh_pairs[i] <= mesh_pairs[i - 1])) {
      throw Error("GlProximity::find: mesh pair " + std::to_string(mesh_pairs[i]) + " (entry " +
                  std::to_string(i) + ") is not an ascending index below the " +
                  std::to_string(all_pairs_.size()) + " mesh pairs");
    }
  }
}

void GlProximity::refit(const ProximityRefitOrder& order, std::span<const float> reach,
                        std::span<const glm::vec3> motion) {
  // No motion is a motion of zero: x + 0 is x, as the CPU's vertex_motion gives for none.
  std::vector<glm::vec4> packed(reach.size());
  for (std::size_t v = 0; v < reach.size(); ++v)
    packed[v] = glm::vec4(motion.empty() ? glm::vec3(0.0f) : motion[v], reach[v]);
  motion_.upload(std::span<const glm::vec4>(packed));
  motion_.bind(kProximityMotionBinding);
  vertex_first_.bind(kProximityVertexFirstBinding);
  boxes_.bind(gpu::kBvhBox);
  bind_storage_buffer(kProximityLevelsBinding, order.buffer);
  refit_.dispatch_covering(node_count_);
  for (const glm::uvec2& level : order.levels) {
    storage_barrier();  // the level reads its children's boxes
    refit_level_.set_uniform("u_first", level.x);
    refit_level_.set_uniform("u_count", level.y);
    refit_level_.dispatch_covering(level.y);
  }
  storage_barrier();  // the search reads the boxes
}

std::vector<collision::ProximityCandidate> GlProximity::find_bound(
    const ProximityRefitOrder& order, std::span<const float> reach,
    std::span<const glm::vec3> motion, std::span<const std::uint32_t> mesh_pairs) {
  check_lists(reach, motion, mesh_pairs);
  search_pairs(mesh_pairs);
  if (item_count_ == 0) return {};
  refit(order, reach, motion);
  mesh_pairs_.bind(gpu::kBodyPair);
  owners_.bind(kProximityOwnersBinding);
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
