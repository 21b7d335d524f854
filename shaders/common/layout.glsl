// Every struct the GPU sees, mirroring include/deformcd/gpu_layout.h byte for byte (std430).
// Include after #version: #include "common/layout.glsl". tests/gl/layout_agreement_test.cpp
// writes every field of every struct from shaders/test/layout_probe.comp and reads it back
// through the C++ structs, so the two cannot drift apart unnoticed.
//
// Binding points are macros, not consts: GLSL 4.30 wants integer literals in layout(binding=).
// Numbered as in the paper's Table 1 (deformcd::gpu::Binding).

#define BINDING_NODE_POSITION 0     // vec4 per node (xyz, w = inverse mass, 0 = fixed); in
                                    // collision passes, float words (MeshInfo.position_*)
#define BINDING_NODE_VELOCITY 1     // vec4 per node (xyz, w = 0)
#define BINDING_SPRING_EDGE 2       // SpringEdge per distinct spring edge
#define BINDING_NODE_FORCE 3        // vec4 per node
#define BINDING_BOX_INFO 4          // Box per leaf box
#define BINDING_COLLISION_RESULT 5  // uint per face: nonzero when the face collides
#define BINDING_FACE_NORMAL 6       // vec4 per surface face (unit normal, w = 0)
#define BINDING_FACE_INFO 7         // Face per surface face
#define BINDING_OBJECT_INFO 8       // ObjectInfo per body (simulation passes)
#define BINDING_MESH_INFO 8         // MeshInfo per mesh (collision passes)
#define BINDING_BOX_FACE_LIST 9     // BoxFace rows, box by box
#define BINDING_FACE_PAIR 10        // intersecting face pairs
#define BINDING_BOX_MASK 11         // int per (box A, box B)
#define BINDING_BODY_PARAMS 12      // BodyParams per body
#define BINDING_NODE_BODY 13        // uint per node: its body
#define BINDING_EDGE_STATE 14          // vec4 per spring edge: unit vector a to b (xyz), q (w)
#define BINDING_NODE_EDGE_OFFSET 15     // uint per node + 1: CSR offsets into the edge terms
#define BINDING_NODE_EDGE_TERM 16       // EdgeTerm per (node, spring), in list order
#define BINDING_TET_INFO 17             // Tetra per tetrahedron with nonzero volume stiffness
#define BINDING_CORNER_FORCE 18         // vec4 per corner slot: a corner's volume force
#define BINDING_NODE_CORNER_OFFSET 19   // uint per node + 1: the node's corner slots
#define BINDING_TET_CORNER_SLOT 20      // uvec4 per tetrahedron: its corners' slots
#define BINDING_FACE_BOXES 21          // uvec2 per face: bit set of the leaf boxes listing it
#define BINDING_BODY_PAIR 22           // BodyPair per pair of different bodies
#define BINDING_COLLISION_COUNTERS 23  // one CollisionCounters
#define BINDING_BOX_ROWS 24            // uvec2 per leaf box: its first row in SSBO 9, row count
#define BINDING_BVH_NODE 25            // BvhNode per BVH node of every body (global indices)
#define BINDING_BVH_BOX 26             // Box per BVH node, refitted every frame
#define BINDING_BODY_BVH 27            // BodyBvh per body
#define BINDING_CANDIDATE_PAIR 28      // uvec2 per candidate face pair (global face indices)
#define BINDING_CONTACT_PAIR 29        // ContactPair per contact constraint of the frame
#define BINDING_CONTACT_SLIDES 30      // uint per acting constraint: bit k, corner k slides on
#define BINDING_NODE_CONTACT_OFFSET 31  // uint per node + 1: CSR offsets
#define BINDING_NODE_CONTACT_LIST 32    // uint per (node, constraint corner): slot 4 p + k
#define BINDING_NODE_CONTACT_COUNT 33   // 2 uint per node: active contacts, volume constraints
#define BINDING_FRAME_START 34          // vec4 per node: frame-start position, w = reach
#define BINDING_NODE_MOTION 35          // vec4 per node: path velocity (xyz, m/s), reach (w, m)
#define BINDING_PROJECTION_START 36     // vec4 per node: x - h v (xyz), path deviation (w)
#define BINDING_CONTACT_IMPULSE 37      // 3 vec4 per acting constraint: given this substep
#define BINDING_NODE_SLID 38            // uint per node: the last substep a contact of it slid in
#define BINDING_NODE_GUARD 39           // uint per node: the last projection a guard named it

// Leaf boxes per body: a 3-level octree, 4 x 4 x 4 leaves (gpu::kLeafBoxesPerBody).
#define LEAF_BOXES_PER_BODY 64u

// BvhNode.face of an internal node (gpu::kBvhInternal).
#define BVH_INTERNAL 0xFFFFFFFFu
// Longest root-to-leaf path a BVH traversal stack holds (collision::kBvhMaxDepth in
// src/core/collision/bvh.h; not a layout, but a bound the host checks before upload).
#define BVH_MAX_DEPTH 64u

// 16 bytes. A surface triangle, outward-oriented (counter-clockwise seen from outside). In a
// collision detector's arrays the vertex indices are local to the mesh, and body is the mesh.
struct Face {
  uint a;
  uint b;
  uint c;
  uint body;  // index of the body (mesh) the face belongs to
};

// 32 bytes. One mesh of a collision detector: where its triangles and leaf-box rows lie in the
// shared arrays and where its vertex positions are read: vertex i's x, y, z are the floats
// position_offset + i x position_stride (+ 1, + 2) of the buffer at BINDING_NODE_POSITION.
struct MeshInfo {
  uint vertex_count;
  uint face_offset;
  uint face_count;
  uint box_face_offset;  // first row of the mesh's BoundingBox Face List
  uint box_face_count;
  uint position_offset;  // in floats
  uint position_stride;  // in floats
  uint pad;
};

// 32 bytes. An axis-aligned box; w components are padding.
struct Box {
  vec4 min;
  vec4 max;
};

// 8 bytes. One row of the paper's BoundingBox Face List (Fig. 7). std430 keeps the array
// stride at 8 (std140 would round it up to 16).
struct BoxFace {
  uint face;
  uint box;
};

// 48 bytes. Where one body's data lies in the shared arrays (the paper's Object Information).
struct ObjectInfo {
  uint node_offset;
  uint node_count;
  uint face_offset;
  uint face_count;
  uint spring_offset;
  uint spring_count;
  uint tet_offset;
  uint tet_count;
  uint box_offset;
  uint box_count;
  uint box_face_offset;
  uint box_face_count;
};

// ContactPair.kind (gpu::kContact*).
#define CONTACT_VERTEX_FACE 0u  // vertex against a face, one-sided along its outward normal
#define CONTACT_EDGE_EDGE 1u    // two edges, apart along the line of their closest points
#define CONTACT_UNTANGLE 2u     // vertex of an intersecting face, out through the other's plane
#define CONTACT_VOLUME 3u       // tetrahedron kept above a floor volume, along its gradient

// 48 bytes. One constraint of the contact response (global node indices): vertex, face a, b, c
// (vertex-face, untangle), edge (a0, a1), edge (b0, b1) (edge-edge) or a tetrahedron's corners
// (volume).
struct ContactPair {
  uvec4 nodes;
  uint kind;
  float thickness;      // m: the distance the constraint keeps (volume: m^3, the least volume)
  float gap;            // m: distance less thickness at the window's start (-inf: untangle, volume)
  float closing_speed;  // m/s: how fast the nodes' straight paths can close the distance
  float side;           // vertex-face: 1 when the vertex started the window in front of the face
  float step_limit;     // volume: m, the most one projection moves a node
  float converge;       // 1: iterate while it is still violated (contact_violated), else 0
  float hold_depth;     // vertex-face: m, how deep behind the face it still holds (>= thickness)
};

// 32 bytes. Per-body parameters of the mass-spring step.
struct BodyParams {
  vec4 carry_velocity;  // xyz: velocity of the body's path (m/s), added to every node
  float damping;        // s: a spring's damping coefficient is damping x its stiffness
  float frozen;         // 1 while substeps skip the body (sim/frozen_bodies.h), else 0
  float pad1;
  float pad2;
};

// 16 bytes. A spring edge: two nodes (global indices, a < b) joined by one or more springs of
// the same rest length, with the damping of node a's body.
struct SpringEdge {
  uint a;
  uint b;
  float rest_length;  // m
  float damping;      // s
};

// 8 bytes. One of a node's springs: its edge and its stiffness signed for the node (+k at the
// edge's node a, -k at its node b).
struct EdgeTerm {
  uint edge;
  float signed_stiffness;  // N/m
};

// 32 bytes. A tetrahedron (global node indices, positively oriented) with its rest volume and
// volume stiffness (0 disables the volume force: the paper's springs-only model).
struct Tetra {
  uint a;
  uint b;
  uint c;
  uint d;
  float rest_volume;  // m^3
  float stiffness;    // Pa / m^3: force on corner i = -stiffness (V - rest_volume) dV/dx_i
  float pad0;
  float pad1;
};

// 8 bytes. Two different bodies whose faces are tested against each other (a < b).
struct BodyPair {
  uint a;
  uint b;
};

// 48 bytes. One intersecting face pair (SSBO 10): global face indices, face_a of the pair's
// lower-numbered body; the intersection segment when the faces are not coplanar.
struct FacePair {
  uint face_a;
  uint face_b;
  uint coplanar;  // 1 when the faces are coplanar (no segment), else 0
  uint pad;
  vec4 segment0;  // xyz: one end of the segment, w = 0
  vec4 segment1;  // xyz: the other end, w = 0
};

// 16 bytes. What a collision pass counts (SSBO 23), reset each pass.
struct CollisionCounters {
  uint face_pairs;       // intersecting face pairs found (may exceed the capacity)
  uint box_pairs;        // overlapping leaf-box pairs (octree)
  uint colliding_faces;  // faces whose flag (SSBO 5) the pass set
  uint candidates;       // face pairs given to the triangle test
};

// 16 bytes. A node of a body's bounding volume hierarchy over its surface faces, one face per
// leaf, in depth-first preorder from the root (children after their parent), global indices.
struct BvhNode {
  uint left;    // child node (internal nodes), else BVH_INTERNAL
  uint right;   // child node (internal nodes), else BVH_INTERNAL
  uint parent;  // BVH_INTERNAL for the root
  uint face;    // the leaf's global face index, BVH_INTERNAL for internal nodes
};

// 16 bytes. Where one body's BVH lies in the node array.
struct BodyBvh {
  uint root;        // global index of the root (= node offset)
  uint node_count;  // 2 x faces - 1
  uint depth;       // longest root-to-leaf path, in edges (stack bound)
  uint pad;
};
