// The proximity search's own buffers (src/gpu/gl/gl_proximity.h), at binding points the
// collision passes (29-34) and the contact response (35, 36) use for their private work
// buffers: every pass binds its buffers before it dispatches. Mirrored in
// src/gpu/gl/gl_proximity.h (kProximity*Binding): change both.
#define BINDING_PROXIMITY_OWNERS 29      // uint per face: collision::primitive_owners bits
#define BINDING_PROXIMITY_MOTION 30      // vec4 per vertex: its motion (xyz, m), its reach (w, m)
#define BINDING_PROXIMITY_PAIR_FIRST 31  // uint per mesh pair + 1: its first work item
#define BINDING_PROXIMITY_COUNTS 32      // uint per work item: its candidates
#define BINDING_PROXIMITY_OFFSETS 33     // uint per work item + 1: exclusive scan of the counts
#define BINDING_PROXIMITY_CANDIDATES 34  // ProximityCandidate per candidate
#define BINDING_PROXIMITY_VERTEX_FIRST 35  // uint per mesh: its first vertex in MOTION's list
#define BINDING_PROXIMITY_LEVELS 36      // uint per internal BVH node, deepest level first
