// GlCollision's passes: the dispatches of each broad phase and of the narrow phases, in order,
// with the barriers between them. run_pass() (gl_collision.cpp) has bound every buffer and
// reset the outputs before, and issues the final barrier after.

#include <epoxy/gl.h>

#include <array>
#include <string>

#include "deformcd/error.h"
#include "gpu/gl/gl_check.h"
#include "gpu/gl/gl_collision.h"

namespace deformcd::gl {

namespace {

// Dispatches `program` over a chunk: x and y cover the chunk's largest counts, z its pairs.
void dispatch_chunk(ComputeProgram& program, const PairChunk& chunk) {
  const std::array<std::uint32_t, 3>& local = program.work_group_size();
  const std::uint32_t groups_x = groups_covering(chunk.max_a, local[0]);
  const std::uint32_t groups_y = groups_covering(chunk.max_b, local[1]);
  if (groups_x == 0 || groups_y == 0) return;
  program.set_uniform("u_pair_first", chunk.first);
  program.dispatch(groups_x, groups_y, chunk.count);
}

}  // namespace

void GlCollision::run(BroadPhase method, const CollisionBuffers& b) {
  switch (method) {
    case BroadPhase::kNone:
      return;
    case BroadPhase::kBrute:
      return run_brute(b);
    case BroadPhase::kOctree:
      return run_octree(b);
    case BroadPhase::kOctreeCompact:
      return run_octree_compact(b);
    case BroadPhase::kBvh:
      return run_bvh(b);
  }
  throw Error("GlCollision::detect: unknown broad phase " +
              std::to_string(static_cast<int>(method)));
}

void GlCollision::run_octree(const CollisionBuffers& b) {
  bb_update_.dispatch_covering(b.box_count);
  storage_barrier();  // bb_collision reads the boxes
  const std::array<std::uint32_t, 3>& local = bb_collision_.work_group_size();
  for (const PairChunk& chunk : b.octree_chunks) {
    bb_collision_.set_uniform("u_pair_first", chunk.first);
    bb_collision_.dispatch(groups_covering(gpu::kLeafBoxesPerBody, local[0]),
                           groups_covering(gpu::kLeafBoxesPerBody, local[1]), chunk.count);
    storage_barrier();  // the narrow phase reads the masks
    dispatch_chunk(tri_tri_octree_, chunk);
    storage_barrier();  // the next chunk's bb_collision rewrites the mask slots read here
  }
}

void GlCollision::run_brute(const CollisionBuffers& b) {
  for (const PairChunk& chunk : b.brute_chunks)
    dispatch_chunk(tri_tri_brute_, chunk);
}

void GlCollision::run_octree_compact(const CollisionBuffers& b) {
  bb_update_.dispatch_covering(b.box_count);
  storage_barrier();  // bb_pair_list reads the boxes
  const std::array<std::uint32_t, 3>& local = bb_pair_list_.work_group_size();
  // No mask: the list holds every chunk's box pairs, so the chunks need no barrier between them.
  for (const PairChunk& chunk : b.brute_chunks) {
    bb_pair_list_.set_uniform("u_pair_first", chunk.first);
    bb_pair_list_.dispatch(groups_covering(gpu::kLeafBoxesPerBody, local[0]),
                           groups_covering(gpu::kLeafBoxesPerBody, local[1]), chunk.count);
  }
  storage_barrier();  // dispatch_args reads counters.box_pairs
  // x covers the rows of the largest leaf box, y the listed box pairs.
  write_dispatch_args(
      {.source = 0,
       .capacity = b.box_pair_capacity,
       .count_axis = 1,
       .other_groups = groups_covering(b.max_box_rows, octree_candidates_.work_group_size()[0])},
      octree_candidates_.work_group_size()[1], kExpandArgsWord);
  command_barrier();
  octree_candidates_.dispatch_indirect(b.dispatch_args.name(), kExpandArgsWord);
  run_candidate_narrow_phase(b);
}

void GlCollision::refit_bvhs(const CollisionBuffers& b) {
  bvh_refit_.dispatch_covering(b.bvh_node_count);
  for (const glm::uvec2& level : b.bvh_levels_ranges) {
    storage_barrier();  // the level reads its children's boxes
    bvh_refit_level_.set_uniform("u_first", level.x);
    bvh_refit_level_.set_uniform("u_count", level.y);
    bvh_refit_level_.dispatch_covering(level.y);
  }
}

void GlCollision::run_bvh(const CollisionBuffers& b) {
  refit_bvhs(b);
  storage_barrier();  // the culling and the traversal read the boxes
  bvh_mesh_pairs_.dispatch_covering(b.mesh_pair_count);
  storage_barrier();  // dispatch_args reads the touching pairs' count
  // x covers the largest query mesh's faces, y the touching pairs (one per work group row).
  write_dispatch_args(
      {.source = 2,
       .capacity = b.mesh_pair_count,
       .count_axis = 1,
       .other_groups = groups_covering(b.max_query_faces, bvh_traverse_.work_group_size()[0])},
      bvh_traverse_.work_group_size()[1], kTraverseArgsWord);
  command_barrier();
  bvh_traverse_.dispatch_indirect(b.dispatch_args.name(), kTraverseArgsWord);
  run_candidate_narrow_phase(b);
}

void GlCollision::run_candidate_narrow_phase(const CollisionBuffers& b) {
  storage_barrier();  // dispatch_args reads counters.candidates
  write_dispatch_args(
      {.source = 1, .capacity = b.candidate_capacity, .count_axis = 0, .other_groups = 1},
      tri_tri_candidates_.work_group_size()[0], kNarrowArgsWord);
  command_barrier();
  tri_tri_candidates_.dispatch_indirect(b.dispatch_args.name(), kNarrowArgsWord);
}

void GlCollision::write_dispatch_args(const IndirectList& list, std::uint32_t local_size,
                                      std::uint32_t word) {
  dispatch_args_.set_uniform("u_source", list.source);
  dispatch_args_.set_uniform("u_capacity", list.capacity);
  dispatch_args_.set_uniform("u_count_axis", list.count_axis);
  dispatch_args_.set_uniform("u_local_size", local_size);
  dispatch_args_.set_uniform("u_max_groups", max_work_groups_[list.count_axis]);
  dispatch_args_.set_uniform("u_other_groups", list.other_groups);
  dispatch_args_.set_uniform("u_args_offset", word);
  dispatch_args_.dispatch(1);
}

}  // namespace deformcd::gl
