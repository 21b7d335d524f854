// GlCollision's side of the GL proximity search (gl_proximity.h): its BVHs, refitted on the
// current positions, are what the search queries.

#include <epoxy/gl.h>

#include "gl_collision.h"

namespace deformcd::gl {

void GlCollision::prepare_proximity() {
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
  // The callers' writes to their position buffers land before the refit reads them.
  memory_barrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  refit_bvhs(b);
  storage_barrier();  // the search reads the boxes
}

}  // namespace deformcd::gl
