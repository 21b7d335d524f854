// Binding points and layout of the GL backend's private work buffers: no C++ struct reads them
// and the CPU backend has no counterpart, so they are not in gpu::Binding / common/layout.glsl.
// Mirrored by src/gpu/gl/collision_work_buffers.h (tests/gl/layout_agreement_test.cpp checks).

// uint[12]: the glDispatchComputeIndirect arguments the GPU writes from its counts
// (collision/dispatch_args.comp), uvec3 triples at DISPATCH_ARGS_EXPAND, _NARROW and _TRAVERSE,
// and at DISPATCH_ARGS_TOUCHING the count of bvh mesh pairs whose root boxes overlap. The host
// clears it before each pass.
#define BINDING_DISPATCH_ARGS 29
// uvec2 per overlapping leaf-box pair of octree-compact: global box indices (64 a + i, 64 b + j).
#define BINDING_BOX_PAIR_LIST 30
// uint per internal BVH node of every mesh: the nodes by depth, deepest level first, for the
// level-by-level refit (collision/bvh_refit_level.comp). Built on the host.
#define BINDING_BVH_LEVELS 31
// uvec2 per bvh mesh pair whose root boxes overlap (a, b): at most every mesh pair.
#define BINDING_TOUCHING_PAIRS 32
// uint per face: the leaf nodes of each mesh's tree in preorder, mesh b's at its face_offset.
// Built on the host.
#define BINDING_BVH_LEAVES 33
// uint per mesh: the lowest vertex of the mesh with a non-finite coordinate, or 0xFFFFFFFF
// (collision/vertex_check.comp). Cleared by the host before each check.
#define BINDING_NON_FINITE 34

// Offsets (in uints) in the dispatch-args buffer.
#define DISPATCH_ARGS_EXPAND 0u    // octree_candidates.comp
#define DISPATCH_ARGS_TOUCHING 3u  // the touching mesh pairs' count, taken with atomicAdd
#define DISPATCH_ARGS_NARROW 4u    // tri_tri_candidates.comp
#define DISPATCH_ARGS_TRAVERSE 8u  // bvh_traverse.comp
