// One work item of the proximity search: face i of mesh pair p's mesh a (items numbered pair by
// pair, pair_first[p] the first of pair p's) queries mesh b's BVH, whose boxes are the faces'
// swept boxes grown by their reaches (proximity_refit*.comp), with its own swept, grown box, and
// each leaf face found gives the candidates of the face pair (emit_face_pair_candidates), as
// CpuProximity::find does for that face: within one mesh only faces of higher index (the pair's
// surface neighbours are left out primitive by primitive, surface_neighbours).
#include "collision/bvh.glsl"
#include "collision/meshes.glsl"
#include "collision/surface.glsl"
#include "common/layout.glsl"
#include "proximity/proximity.glsl"
#include "proximity/proximity_buffers.glsl"

layout(std430, binding = BINDING_BODY_PAIR) readonly buffer MeshPairs {
  BodyPair mesh_pairs[];
};
layout(std430, binding = BINDING_BODY_BVH) readonly buffer BodyBvhs {
  BodyBvh mesh_bvhs[];
};
layout(std430, binding = BINDING_PROXIMITY_OWNERS) readonly buffer Owners {
  uint owners[];
};
layout(std430, binding = BINDING_PROXIMITY_PAIR_FIRST) readonly buffer PairFirst {
  uint pair_first[];
};

uniform uint u_pair_count;
uniform uint u_item_count;

// broad_phase.glsl declares it for is_first_box_pair, which the search does not call.
bool mask_says_overlap(uint mask_slot, uint box_a, uint box_b) { return false; }

// The query's face a (swept once: g_sa, g_pa) and the rules of bvh_visit.
Face g_fa;
SweptFace g_sa;
SweptPrimitives g_pa;
uint g_index_a;
uint g_owners_a;
bool g_self;

// Within one mesh each face pair once (a face with itself pairs only surface neighbours, which
// the emit leaves out).
void bvh_visit(uint index_b) {
  if (g_self && index_b <= g_index_a) return;
  const Face fb = faces[index_b];
  const SweptFace sb = sweep_face(fb);
  emit_face_pair_candidates(g_fa, g_sa, g_pa, g_index_a, g_owners_a, fb, sb, sweep_primitives(sb),
                            index_b, owners[index_b]);
}

// Runs work item `item` (< u_item_count).
void run_proximity_item(uint item) {
  // The pair whose items contain `item`: the last p with pair_first[p] <= item.
  uint lo = 0u, hi = u_pair_count;
  while (hi - lo > 1u) {
    const uint mid = (lo + hi) / 2u;
    if (pair_first[mid] <= item) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  const BodyPair pair = mesh_pairs[lo];
  const MeshInfo mesh_a = meshes[pair.a];
  g_index_a = mesh_a.face_offset + (item - pair_first[lo]);
  g_fa = faces[g_index_a];
  g_owners_a = owners[g_index_a];
  g_self = pair.a == pair.b;
  g_sa = sweep_face(g_fa);
  g_pa = sweep_primitives(g_sa);
  query_bvh(mesh_bvhs[pair.b].root, g_sa.box);
}
