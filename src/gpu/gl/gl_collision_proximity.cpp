// GlCollision's proximity phase: the search on the GPU (gl_proximity.h) refits boxes of its own
// over this backend's BVH topology (nodes, the meshes' trees and their refit order) and queries
// them on the positions a pass stages; a widened search runs on the host (cpu::CpuProximity)
// over the host copy of the same trees, which the upkeep rebuilds keep equal to the GPU's.

#include <epoxy/gl.h>

#include "cpu/cpu_proximity.h"
#include "cpu/executor.h"
#include "deformcd/error.h"
#include "gpu/gl/gl_collision.h"

namespace deformcd::gl {

ProximityRefitOrder GlCollision::prepare_proximity() {
  // A pending pass may still be rerun on the staged positions; staging anew must wait for it.
  complete_pass();
  CollisionBuffers& b = buffers("prepare_proximity");
  stage_positions(b);
  if (upkeep_pending_) {
    upkeep_ = measured_bvh_upkeep(*upkeep_pending_);
    upkeep_pending_.reset();
  }
  staging_.bind();
  b.bind();
  // The callers' writes to their position buffers land before the search reads them.
  memory_barrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  return {b.bvh_levels.name(), b.bvh_levels_ranges};
}

std::vector<collision::ProximityCandidate> GlCollision::find_proximity(
    const collision::ProximityQuery& query, std::vector<float>& distances) {
  const ProximityRefitOrder order = prepare_proximity();
  if (!proximity_) {
    collision::CollisionData tables;  // what the search's own buffers are made from
    tables.faces = upkeep_.faces();
    tables.meshes = upkeep_.meshes();
    tables.mesh_pairs = mesh_pairs_;
    proximity_ = std::make_unique<GlProximity>(device_info_, tables);
  }
  std::vector<collision::ProximityCandidate> found =
      proximity_->find_bound(order, query.flat_reach, query.flat_motion, query.mesh_pairs);
  if (host_proximity_) host_proximity_->forget_boxes();
  distances.clear();
  return found;
}

std::vector<collision::ProximityCandidate> GlCollision::widen_proximity(
    const collision::ProximityQuery& query, std::span<const std::array<std::uint32_t, 2>> widened,
    std::vector<float>& distances) {
  if (!proximity_) throw Error("GL collision: widen_proximity before a proximity search");
  if (!host_proximity_) {
    if (!executor_) executor_ = std::make_shared<cpu::Executor>(0);
    host_proximity_ = std::make_unique<cpu::CpuProximity>(upkeep_, mesh_pairs_, executor_);
  }
  return host_proximity_->widen(query.positions, query.motion, query.reach, query.mesh_pairs,
                                widened, distances);
}

}  // namespace deformcd::gl
