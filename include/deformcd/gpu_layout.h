#pragma once
/// \file gpu_layout.h
/// Every struct the GPU sees, byte for byte. Mirrored in shaders/common/layout.glsl (std430);
/// the static_asserts below and the GL layout test keep the two in step.
/// Public because applications that render straight from our buffers need the layouts.
///
/// The paper's Table 1 numbers the SSBOs; we keep its numbering as binding points.

#include <cstddef>
#include <cstdint>

#include <glm/vec4.hpp>

namespace deformcd::gpu {

/// SSBO binding points, numbered as in the paper's Table 1.
enum Binding : std::uint32_t {
  kNodePosition = 0,     ///< glm::vec4 per node (xyz, w = inverse mass, 0 = fixed)
  kNodeVelocity = 1,     ///< glm::vec4 per node (xyz, w = 0)
  kSpringEdge = 2,       ///< SpringEdge per distinct spring edge (the GL mass-spring step)
  kNodeForce = 3,        ///< glm::vec4 per node
  kBoxInfo = 4,          ///< Box per leaf box
  kCollisionResult = 5,  ///< uint per face: nonzero when the face collides
  kFaceNormal = 6,       ///< glm::vec4 per surface face (unit normal, w = 0)
  kFaceInfo = 7,         ///< Face per surface face
  kObjectInfo = 8,       ///< ObjectInfo per body (simulation passes)
  kMeshInfo = 8,         ///< MeshInfo per mesh (collision passes; each pass binds its own)
  kBoxFaceList = 9,      ///< BoxFace rows, box by box
  kFacePair = 10,        ///< intersecting face pairs
  kBoxMask = 11,         ///< int per (box A, box B)
  // Beyond the paper's 12: what the mass-spring shaders need besides them. The paper computes
  // each spring and gathers per node over a spring list; these compute each spring edge once
  // (src/core/sim/node_force_lists.h) and lay the tetrahedron corners out node by node.
  kBodyParams = 12,        ///< BodyParams per body
  kNodeBody = 13,          ///< uint per node: its body
  kEdgeState = 14,         ///< glm::vec4 per spring edge: unit vector a to b (xyz), q (w)
  kNodeEdgeOffset = 15,    ///< uint per node + 1: CSR offsets into kNodeEdgeTerm
  kNodeEdgeTerm = 16,      ///< EdgeTerm per (node, spring), in the node's spring-list order
  kTetInfo = 17,           ///< Tetra per tetrahedron with nonzero volume stiffness
  kCornerForce = 18,       ///< glm::vec4 per corner slot: a tetrahedron corner's volume force
  kNodeCornerOffset = 19,  ///< uint per node + 1: the node's corner slots, contiguous
  kTetCornerSlot = 20,     ///< glm::uvec4 per kTetInfo tetrahedron: its corners' slots
  // Beyond the paper's 12: what the collision shaders need besides them.
  kFaceBoxes = 21,          ///< glm::uvec2 per face: bit set of the leaf boxes listing it
  kBodyPair = 22,           ///< BodyPair per pair of different bodies
  kCollisionCounters = 23,  ///< one CollisionCounters
  kBoxRows = 24,            ///< glm::uvec2 per leaf box: its first row in SSBO 9, row count
  kBvhNode = 25,            ///< BvhNode per BVH node of every body (global indices)
  kBvhBox = 26,             ///< Box per BVH node, refitted every frame
  kBodyBvh = 27,            ///< BodyBvh per body
  kCandidatePair = 28,      ///< glm::uvec2 per candidate face pair (global face indices)
  // Contact response (beyond the paper).
  kContactPair = 29,  ///< ContactPair per contact constraint of the frame
  /// uint per constraint acting in the projection (a, its place in the acting list, ascending):
  /// bit k set where the contact slides on at corner k in the last sweep (the slide stamps'
  /// source)
  kContactSlides = 30,
  kNodeContactOffset = 31,  ///< uint per node + 1: CSR offsets into kNodeContactList
  kNodeContactList = 32,    ///< uint per (node, constraint corner): the slot 4 p + k, sorted
  kNodeContactCount = 33,   ///< two uint per node: its active contacts, volume constraints
  kFrameStart = 34,         ///< glm::vec4 per node: position at the frame's start, w = reach
  kNodeMotion = 35,         ///< glm::vec4 per node: path velocity (xyz, m/s), reach (w, m)
  /// glm::vec4 per node at a projection's start: position - h x velocity (xyz), distance from
  /// its straight path (w, m) (response::projection_start)
  kProjectionStart = 36,
  /// three glm::vec4 per acting constraint (3 a to 3 a + 2): what it has given in the substep's
  /// iterations so far (normal speed, push, the first iteration's approach; friction, the first
  /// iteration's slip; the hold; response::solve_contact)
  kContactImpulse = 37,
  /// uint per node: the last substep (a projection's count, from 1) in which one of its
  /// contacts slid (response::solve_contact's slide flag, stamped after the last sweep); free
  /// nodes only
  kNodeSlid = 38,
  /// uint per node: the last projection (a count, from 1) in which an active contact that
  /// guards volume constraints named it (response::guards_volumes); its volume constraints act
  /// in that projection whatever their volume (response::volume_watched)
  kNodeGuard = 39,
};

/// BvhNode::face of an internal node.
inline constexpr std::uint32_t kBvhInternal = 0xFFFFFFFFu;

/// Leaf boxes per body: a 3-level octree over the body's rest pose, 4 x 4 x 4 leaves (paper).
inline constexpr std::uint32_t kLeafBoxesPerBody = 64;

/// 16 bytes. One spring between two nodes (global indices): rest length and stiffness. Its
/// damping is stiffness-proportional with its body's coefficient (BodyParams::damping).
/// SimulationState's springs; both backends compute each spring edge once instead (SpringEdge,
/// EdgeTerm), so no shader reads this struct.
struct Spring {
  std::uint32_t a;    ///< node at one end (global index)
  std::uint32_t b;    ///< node at the other end
  float rest_length;  ///< m
  float stiffness;    ///< N/m
};
static_assert(sizeof(Spring) == 16);
static_assert(offsetof(Spring, rest_length) == 8);

/// 16 bytes. A surface triangle, outward-oriented (counter-clockwise seen from outside). In a
/// world's arrays the vertex indices are global (into every body's nodes); in a collision
/// detector's they are local to the mesh, and body is the mesh.
struct Face {
  std::uint32_t a;     ///< first vertex
  std::uint32_t b;     ///< second vertex
  std::uint32_t c;     ///< third vertex
  std::uint32_t body;  ///< index of the body (mesh) the face belongs to
};
static_assert(sizeof(Face) == 16);

/// 32 bytes. One mesh of a collision detector: where its triangles and leaf-box rows lie in
/// the shared arrays and where its vertex positions are read (the faces' vertex indices are
/// local to the mesh).
struct MeshInfo {
  std::uint32_t vertex_count;     ///< vertices of the mesh
  std::uint32_t face_offset;      ///< first triangle in the shared face array
  std::uint32_t face_count;       ///< triangles of the mesh
  std::uint32_t box_face_offset;  ///< first row of the mesh's BoundingBox Face List
  std::uint32_t box_face_count;   ///< rows in the BoundingBox Face List
  /// GL: vertex i's x, y, z are floats position_offset + i x position_stride (+ 1, + 2) of the
  /// position buffer bound at kNodePosition. Unused on the CPU, which reads the caller's arrays.
  std::uint32_t position_offset;
  std::uint32_t position_stride;  ///< floats from one vertex to the next
  std::uint32_t pad;              ///< std430 padding
};
static_assert(sizeof(MeshInfo) == 32);
static_assert(offsetof(MeshInfo, position_offset) == 20);

/// 32 bytes. An axis-aligned box; w components are padding.
struct Box {
  glm::vec4 min;  ///< smallest corner (w: padding)
  glm::vec4 max;  ///< largest corner (w: padding)
};
static_assert(sizeof(Box) == 32);
static_assert(offsetof(Box, max) == 16);

/// 8 bytes. One row of the paper's BoundingBox Face List (Fig. 7): global face index, and the
/// leaf box's index within its body (0-63, octree order).
struct BoxFace {
  std::uint32_t face;  ///< global face index
  std::uint32_t box;   ///< leaf box within the body, 0-63 in octree order
};
static_assert(sizeof(BoxFace) == 8);

/// 8 bytes. Two different bodies whose faces are tested against each other (a < b).
struct BodyPair {
  std::uint32_t a;  ///< the lower-numbered body
  std::uint32_t b;  ///< the other body
};
static_assert(sizeof(BodyPair) == 8);

/// 48 bytes. One intersecting face pair (SSBO 10): global face indices, face_a of the pair's
/// lower-numbered body; the intersection segment when the faces are not coplanar.
struct FacePair {
  std::uint32_t face_a;    ///< face of the lower-numbered body (global index)
  std::uint32_t face_b;    ///< face of the other body (global index)
  std::uint32_t coplanar;  ///< 1 when the faces are coplanar (no segment), else 0
  std::uint32_t pad;       ///< std430 padding
  glm::vec4 segment0;      ///< xyz: one end of the segment, w = 0
  glm::vec4 segment1;      ///< xyz: the other end, w = 0
};
static_assert(sizeof(FacePair) == 48);
static_assert(offsetof(FacePair, segment0) == 16);

/// 16 bytes. A node of a body's bounding volume hierarchy over its surface faces, one face per
/// leaf. Nodes are stored in depth-first preorder from the root (a node's children come after
/// it), with global indices; refitting in reverse order visits children before parents.
struct BvhNode {
  std::uint32_t left;    ///< child node (internal nodes), else kBvhInternal
  std::uint32_t right;   ///< child node (internal nodes), else kBvhInternal
  std::uint32_t parent;  ///< kBvhInternal for the root
  std::uint32_t face;    ///< the leaf's global face index, kBvhInternal for internal nodes
};
static_assert(sizeof(BvhNode) == 16);

/// 16 bytes. Where one body's BVH lies in the node array.
struct BodyBvh {
  std::uint32_t root;        ///< global index of the root (= node_offset)
  std::uint32_t node_count;  ///< 2 x faces - 1
  std::uint32_t depth;       ///< longest root-to-leaf path, in edges (stack bound)
  std::uint32_t pad;         ///< std430 padding
};
static_assert(sizeof(BodyBvh) == 16);

/// 16 bytes. What a collision pass counts, on the device (SSBO 23), reset each pass.
struct CollisionCounters {
  std::uint32_t face_pairs;       ///< intersecting face pairs found (may exceed the capacity)
  std::uint32_t box_pairs;        ///< overlapping leaf-box pairs (octree)
  std::uint32_t colliding_faces;  ///< faces whose flag (SSBO 5) the pass set
  std::uint32_t candidates;       ///< face pairs given to the triangle test
};
static_assert(sizeof(CollisionCounters) == 16);

/// 48 bytes. Where one body's data lies in the shared arrays (the paper's Object Information).
struct ObjectInfo {
  std::uint32_t node_offset;      ///< first node in the node arrays
  std::uint32_t node_count;       ///< nodes of the body
  std::uint32_t face_offset;      ///< first surface face in the face array
  std::uint32_t face_count;       ///< surface faces of the body
  std::uint32_t spring_offset;    ///< first spring in the spring array
  std::uint32_t spring_count;     ///< springs of the body
  std::uint32_t tet_offset;       ///< first tetrahedron in the tetrahedron array
  std::uint32_t tet_count;        ///< tetrahedra of the body
  std::uint32_t box_offset;       ///< first leaf box in the box array
  std::uint32_t box_count;        ///< leaf boxes of the body (64)
  std::uint32_t box_face_offset;  ///< first row in the BoundingBox Face List
  std::uint32_t box_face_count;   ///< rows of the body in that list
};
static_assert(sizeof(ObjectInfo) == 48);
static_assert(offsetof(ObjectInfo, box_offset) == 32);

/// 16 bytes. A spring edge (kSpringEdge): two nodes (global indices, a < b) joined by one or
/// more springs of the same rest length, with the damping of node a's body. The GL step computes
/// its state (u, q) once for all of its springs (sim::spring_edge_state).
struct SpringEdge {
  std::uint32_t a;    ///< the lower node (global index)
  std::uint32_t b;    ///< the higher node
  float rest_length;  ///< m
  float damping;      ///< s: stiffness-proportional damping coefficient
};

/// 8 bytes. One of a node's springs (kNodeEdgeTerm): its edge, and its stiffness signed for the
/// node (+k at the edge's node a, -k at its node b), so that the spring's force on the node is
/// (signed_stiffness q) u (sim::spring_term).
struct EdgeTerm {
  std::uint32_t edge;      ///< index into the spring edges (kSpringEdge)
  float signed_stiffness;  ///< N/m
};

/// 32 bytes. A tetrahedron (global node indices, positively oriented) with its rest volume and
/// volume stiffness: the volume force that keeps it from collapsing or inverting, which edge
/// springs alone cannot (a flat tetrahedron's apex can snap through its base).
struct Tetra {
  std::uint32_t a;    ///< first corner (global node index)
  std::uint32_t b;    ///< second corner
  std::uint32_t c;    ///< third corner
  std::uint32_t d;    ///< fourth corner
  float rest_volume;  ///< m^3
  /// Pa / m^3: the body's volume stiffness over the tetrahedron's mean rest edge length cubed;
  /// the force on corner i is -stiffness (V - rest_volume) dV/dx_i. 0 disables it (the
  /// paper's springs-only model).
  float stiffness;
  float pad0;  ///< std430 padding
  float pad1;  ///< std430 padding
};
static_assert(sizeof(Tetra) == 32);
static_assert(sizeof(SpringEdge) == 16);
static_assert(offsetof(SpringEdge, damping) == 12);
static_assert(sizeof(EdgeTerm) == 8);
static_assert(offsetof(Tetra, rest_volume) == 16);

/// ContactPair::kind: a vertex against a face, one-sided along the face's outward normal.
inline constexpr std::uint32_t kContactVertexFace = 0;
/// ContactPair::kind: two edges, pushed apart along the line between their closest points.
inline constexpr std::uint32_t kContactEdgeEdge = 1;
/// ContactPair::kind: a vertex of a face that intersects another body's face, pushed out
/// through that face's plane (untangling from the exact intersection list).
inline constexpr std::uint32_t kContactUntangle = 2;
/// ContactPair::kind: a tetrahedron kept from collapsing below a floor volume (its corners a,
/// b, c, d as gpu::Tetra names them), pushed back along its volume's gradient.
inline constexpr std::uint32_t kContactVolume = 3;

/// 48 bytes. One constraint of the contact response (global node indices): kContactVertexFace
/// and kContactUntangle: vertex, face a, b, c; kContactEdgeEdge: edge (a0, a1), edge (b0, b1);
/// kContactVolume: the tetrahedron's corners.
struct ContactPair {
  std::uint32_t nodes[4];  ///< global node indices, as the struct's comment orders them
  std::uint32_t kind;      ///< one of the gpu::kContact* constants
  /// m: the distance the constraint keeps (kContactVolume: m^3, the least volume it keeps).
  float thickness;
  /// m: the primitives' distance less the thickness where the search window starts (-inf for
  /// kContactUntangle and kContactVolume: always awake).
  float gap;
  /// m/s: the most the nodes' straight paths (their velocities where the window starts) can
  /// close of the distance per second (collision::closing_speed).
  float closing_speed;
  /// kContactVertexFace: 1 when the vertex was in front of the face (on its outward side) where
  /// the window starts, else 0. Only a vertex that started in front is held off the face; one
  /// that started behind it is on the far side of a thin part, or inside the body (where the
  /// untangling constraints take it out). kContactEdgeEdge: which side of the second edge the
  /// first passes on where the window starts (response::edge_edge_start_side: 1 or -1; 0 where
  /// the closest points are an edge's end or the edges nearly parallel), so that edges that go
  /// through each other within the window are taken back. kContactVolume: 1 when the
  /// tetrahedron is thin, its least rest height (3 x its volume over its largest face's area)
  /// below its body's thickness, so that a guarding contact's push may turn it inside out: only
  /// then do guards watch its floor (response::volume_watched). 0 for other kinds.
  float side;
  /// kContactVolume: m, the most one projection moves a node (the tetrahedron's mean rest edge
  /// length: a tetrahedron collapsed to a line has gradients near zero). 0 for other kinds.
  float step_limit;
  /// 1: a projection iterates beyond the iterations asked while this constraint is still
  /// violated (response::contact_violated); 0 for a constraint between bodies the frame's exact
  /// pass found intersecting (taken apart over substeps), and for untangling constraints.
  float converge;
  /// kContactVertexFace: m, how deep behind the face the vertex may be and still be held in
  /// front of it (deeper is a tunnel: the untangling constraints take it out); at least the
  /// thickness (0 or less: the thickness). kContactEdgeEdge: how far through each other edges
  /// with a side may have gone and still be taken back. The world sets a body's own thickness
  /// for its self pairs whose thickness the rest-distance rule cut to half their rest
  /// distance, so that a vertex (an edge) pushed past such a thin guard within a substep is
  /// still brought back. 0 for other kinds.
  float hold_depth;
};
static_assert(sizeof(ContactPair) == 48);
static_assert(offsetof(ContactPair, kind) == 16);

/// 32 bytes. Per-body parameters of the mass-spring step.
struct BodyParams {
  glm::vec4 carry_velocity;  ///< xyz: velocity of the body's path (m/s), added to every node
  float damping;             ///< s: a spring's damping coefficient is damping x its stiffness
  /// 1 while substeps skip the body, else 0 (the GL backend sets it on its own copy from
  /// sim::FrozenBodies: every node fixed, no carry velocity; a state's value is not read).
  float frozen;
  float pad1;  ///< std430 padding
  float pad2;  ///< std430 padding
};
static_assert(sizeof(BodyParams) == 32);
static_assert(offsetof(BodyParams, damping) == 16);

}  // namespace deformcd::gpu
