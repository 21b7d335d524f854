// The proximity search's own buffers (src/gpu/gl/gl_proximity.h, ProximityBuffers), at binding
// points the collision passes use for their private work buffers: every pass binds its buffers
// before it dispatches. Mirrored in src/gpu/gl/gl_proximity.h (kProximity*Binding): change both.
#define BINDING_PROXIMITY_OWNERS 29      // uint per face: collision::primitive_owners bits
#define BINDING_PROXIMITY_REACH 30       // vec4 per mesh: its drift (xyz, m), its reach (w, m)
#define BINDING_PROXIMITY_PAIR_FIRST 31  // uint per mesh pair + 1: its first work item
#define BINDING_PROXIMITY_COUNTS 32      // uint per work item: its candidates
#define BINDING_PROXIMITY_OFFSETS 33     // uint per work item + 1: exclusive scan of the counts
#define BINDING_PROXIMITY_CANDIDATES 34  // ProximityCandidate per candidate
