#version 430
// The bvh broad phase's traversal, after collision/bvh_refit.comp refitted every mesh's tree and
// collision/bvh_mesh_pairs.comp listed the mesh pairs whose root boxes overlap. Work group
// (x, p) takes touching pair p (grid-stride over the list when it outnumbers the dispatch): its
// mesh with fewer faces queries the other's tree, invocation x taking the x-th leaf of its own
// tree in preorder (SSBO 33) and querying with the leaf's box (its face's box). Every leaf face
// of the other tree whose box overlaps it becomes a candidate pair
// (collision/candidate_pairs.glsl), face_a of the lower-numbered mesh; each face pair of the two
// meshes is thus appended at most once. Leaves in preorder rather than faces in mesh order put
// neighbouring faces in neighbouring lanes, whose queries take the same paths down the other
// tree. Measured on llvmpipe with phase1 and sixteen bunnies: 25% faster than all nodes in
// preorder (leaves interleaved with idle internal nodes' lanes), which were 10% faster than
// faces in mesh order. Dispatched indirectly (collision/dispatch_args.comp): x over the largest
// face count of a pair's smaller mesh, y over the touching pairs; invocations past their pair's
// faces idle.
#include "collision/broad_phase.glsl"
#include "collision/bvh.glsl"
#include "collision/candidate_pairs.glsl"
#include "collision/gl_work_buffers.glsl"
#include "collision/meshes.glsl"
#include "common/layout.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_DISPATCH_ARGS) readonly buffer DispatchArgs {
  uint dispatch_args[];  // the touching pairs' count at DISPATCH_ARGS_TOUCHING
};
layout(std430, binding = BINDING_TOUCHING_PAIRS) readonly buffer TouchingPairs {
  uvec2 touching_pairs[];  // mesh pairs (a, b) whose root boxes overlap
};
layout(std430, binding = BINDING_BVH_LEAVES) readonly buffer BvhLeaves {
  uint bvh_leaves[];  // per mesh (from its face_offset), its tree's leaves in preorder
};
layout(std430, binding = BINDING_BODY_BVH) readonly buffer BodyBvhs {
  BodyBvh mesh_bvhs[];
};

// broad_phase.glsl declares it for is_first_box_pair, which this shader does not call.
bool mask_says_overlap(uint mask_slot, uint box_a, uint box_b) { return false; }

uint g_query_face;      // the leaf face this invocation queries with
bool g_query_is_lower;  // whether it belongs to the mesh pair's lower-numbered mesh

void bvh_visit(uint face) {
  if (g_query_is_lower) {
    append_candidate(g_query_face, face);
  } else {
    append_candidate(face, g_query_face);
  }
}

void main() {
  const uint count = dispatch_args[DISPATCH_ARGS_TOUCHING];
  const uint x = gl_GlobalInvocationID.x;
  for (uint p = gl_WorkGroupID.y; p < count; p += gl_NumWorkGroups.y) {
    const uvec2 pair = touching_pairs[p];
    const BodyBvh ta = mesh_bvhs[pair.x];
    const BodyBvh tb = mesh_bvhs[pair.y];
    const MeshInfo a = meshes[pair.x];
    const MeshInfo b = meshes[pair.y];
    g_query_is_lower = a.face_count <= b.face_count;
    const MeshInfo query = g_query_is_lower ? a : b;
    if (x >= query.face_count) continue;
    const uint leaf = bvh_leaves[query.face_offset + x];
    g_query_face = bvh_nodes[leaf].face;
    query_bvh(g_query_is_lower ? tb.root : ta.root, bvh_boxes[leaf]);
  }
}
