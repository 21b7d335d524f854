// Binding points and layout of the GL contact response's private work buffers: the projection's
// compaction of its acting constraints and touched nodes (the CPU backend keeps the same lists in
// host vectors), so they are not in gpu::Binding / common/layout.glsl. Mirrored by
// src/gpu/gl/response_work_buffers.h (tests/gl/layout_agreement_test.cpp checks).

// uint per constraint p: the activity pass's flag (1: acts in this projection, else 0), which
// the compaction pass rewrites to 1 + p's place in the acting list (0: does not act).
#define BINDING_CONTACT_ACTING 40
// uint per acting constraint: the acting constraints, ascending (the contacts first: the volume
// constraints are the list's last). Entry a's slide bits are BINDING_CONTACT_SLIDES' a, its
// impulses 3 a to 3 a + 2 of BINDING_CONTACT_IMPULSE.
#define BINDING_ACTING_LIST 41
// uint per entry of BINDING_NODE_CONTACT_LIST: node n's active slots (4 a + corner, a an acting
// list place) from its list offset on, in its list's order: its acting contacts' (count 2 n),
// then its acting volume constraints' (count 2 n + 1).
#define BINDING_NODE_ACTIVE_SLOT 42
// uint per touched node (a node of an acting constraint), in no particular order: the slide pass
// visits them; each writes only its own node, so the order changes no result.
#define BINDING_TOUCHED_NODE 43
// uint[14]: the counts and flags below, and the glDispatchComputeIndirect triples that
// response/contact_dispatch_args.comp writes from the counts.
#define BINDING_RESPONSE_STATE 44
// uint per acting constraint: the sweep's order (acting places colour by colour, the contacts'
// colours first; src/core/response/sweep_order.h, made on the host).
#define BINDING_SWEEP_ORDER 45
// uint per colour + 1: colour c's places are BINDING_SWEEP_ORDER's [c, c + 1) entries of this.
#define BINDING_SWEEP_COLOURS 46

// Offsets (in uints) in the state buffer.
#define RESPONSE_ACTING_CONTACTS 0u     // acting contacts: the acting list's first part
#define RESPONSE_ACTING_TOTAL 1u        // acting constraints in all
#define RESPONSE_TOUCHED_NODES 2u       // touched nodes, taken with atomicAdd
#define RESPONSE_STRAY_FLAG 3u          // 1: a node strayed beyond its reach
#define RESPONSE_RESIDUAL_FLAG 4u       // 1: an acting constraint is still violated
#define RESPONSE_RESIDUAL_ARGS 8u       // contact_residual.comp over the acting constraints
#define RESPONSE_SLIDE_PASS_ARGS 11u    // contact_slide.comp over the touched nodes
