// GlCollision's side of the GL proximity search (gl_proximity.h): its BVH topology (nodes, the
// meshes' trees and their refit order) and its staged positions are what the search refits its
// own boxes over and queries.

#include <epoxy/gl.h>

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

}  // namespace deformcd::gl
