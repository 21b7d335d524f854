// GLSL std430 (shaders/common/layout.glsl) and C++ (deformcd/gpu_layout.h) agree: the probe
// shader writes probe(i, k) = 1000 (i + 1) + k into field k of element i of every struct array,
// and we read the buffers back through the C++ structs. A wrong offset, size or array stride
// moves some value to another field or element.

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/collision/bvh.h"
#include "deformcd/gl/ssbo.h"
#include "deformcd/gpu_layout.h"
#include "gl/gl_test_context.h"
#include "gpu/gl/collision_work_buffers.h"
#include "gpu/gl/compute_program.h"
#include "gpu/gl/response_work_buffers.h"

namespace deformcd::gl {
namespace {

struct ProbeOutput {
  std::vector<gpu::SpringEdge> edges;
  std::vector<gpu::Face> faces;
  std::vector<gpu::Box> boxes;
  std::vector<gpu::BoxFace> box_faces;
  std::vector<gpu::ObjectInfo> objects;
  std::vector<gpu::BodyParams> body_params;
  std::vector<gpu::Tetra> tets;
  std::vector<gpu::BodyPair> body_pairs;
  std::vector<gpu::FacePair> face_pairs;
  std::vector<gpu::CollisionCounters> counters;
  std::vector<gpu::BvhNode> bvh_nodes;
  std::vector<gpu::BodyBvh> body_bvhs;
  std::vector<gpu::MeshInfo> meshes;
  std::vector<gpu::ContactPair> contact_pairs;
  std::vector<gpu::EdgeTerm> edge_terms;
  // The BINDING_* macros in gpu::Binding order (kBindingCount of them), then the constants
  // (kConstantCount).
  std::vector<std::uint32_t> bindings;
};

constexpr std::uint32_t kBindingCount = gpu::kNodeGuard + 1;
constexpr std::uint32_t kConstantCount = 32;

// Runs shaders/test/layout_probe.comp over `count` elements of each struct.
ProbeOutput run_layout_probe(std::uint32_t count) {
  ComputeProgram program("test/layout_probe.comp");
  const Ssbo<gpu::SpringEdge> edges(count);
  const Ssbo<gpu::Face> faces(count);
  const Ssbo<gpu::Box> boxes(count);
  const Ssbo<gpu::BoxFace> box_faces(count);
  const Ssbo<gpu::ObjectInfo> objects(count);
  const Ssbo<std::uint32_t> bindings(kBindingCount + kConstantCount);
  const Ssbo<gpu::BodyParams> body_params(count);
  const Ssbo<gpu::Tetra> tets(count);
  const Ssbo<gpu::BodyPair> body_pairs(count);
  const Ssbo<gpu::FacePair> face_pairs(count);
  const Ssbo<gpu::CollisionCounters> counters(count);
  const Ssbo<gpu::BvhNode> bvh_nodes(count);
  const Ssbo<gpu::BodyBvh> body_bvhs(count);
  const Ssbo<gpu::MeshInfo> meshes(count);
  const Ssbo<gpu::ContactPair> contact_pairs(count);
  const Ssbo<gpu::EdgeTerm> edge_terms(count);
  edges.bind(0);
  faces.bind(1);
  boxes.bind(2);
  box_faces.bind(3);
  objects.bind(4);
  bindings.bind(5);
  body_params.bind(6);
  tets.bind(7);
  body_pairs.bind(8);
  face_pairs.bind(9);
  counters.bind(10);
  bvh_nodes.bind(11);
  body_bvhs.bind(12);
  meshes.bind(13);
  contact_pairs.bind(14);
  edge_terms.bind(15);
  program.set_uniform("u_count", count);
  program.dispatch_covering(count);
  return {
      edges.download(),      faces.download(),         boxes.download(),      box_faces.download(),
      objects.download(),    body_params.download(),   tets.download(),       body_pairs.download(),
      face_pairs.download(), counters.download(),      bvh_nodes.download(),  body_bvhs.download(),
      meshes.download(),     contact_pairs.download(), edge_terms.download(), bindings.download()};
}

std::uint32_t probe(std::uint32_t i, std::uint32_t k) {
  return 1000 * (i + 1) + k;
}
float probef(std::uint32_t i, std::uint32_t k) {
  return static_cast<float>(probe(i, k));
}
glm::vec4 probe4(std::uint32_t i, std::uint32_t k) {
  return {probef(i, k), probef(i, k + 1), probef(i, k + 2), probef(i, k + 3)};
}

class LayoutAgreementTest : public test_support::GlTest {};

TEST_F(LayoutAgreementTest, EveryFieldOfEveryStructRoundTrips) {
  constexpr std::uint32_t kCount = 5;  // several elements, so that strides matter
  const ProbeOutput out = run_layout_probe(kCount);
  for (std::uint32_t i = 0; i < kCount; ++i) {
    SCOPED_TRACE("element " + std::to_string(i));
    const gpu::SpringEdge& s = out.edges[i];
    EXPECT_EQ(s.a, probe(i, 0));
    EXPECT_EQ(s.b, probe(i, 1));
    EXPECT_EQ(s.rest_length, probef(i, 2));
    EXPECT_EQ(s.damping, probef(i, 3));

    const gpu::EdgeTerm& term = out.edge_terms[i];
    EXPECT_EQ(term.edge, probe(i, 0));
    EXPECT_EQ(term.signed_stiffness, probef(i, 1));

    const gpu::Face& f = out.faces[i];
    EXPECT_EQ(f.a, probe(i, 0));
    EXPECT_EQ(f.b, probe(i, 1));
    EXPECT_EQ(f.c, probe(i, 2));
    EXPECT_EQ(f.body, probe(i, 3));

    EXPECT_EQ(out.boxes[i].min, probe4(i, 0));
    EXPECT_EQ(out.boxes[i].max, probe4(i, 4));

    EXPECT_EQ(out.box_faces[i].face, probe(i, 0));
    EXPECT_EQ(out.box_faces[i].box, probe(i, 1));

    const gpu::ObjectInfo& o = out.objects[i];
    const std::uint32_t fields[] = {o.node_offset, o.node_count,      o.face_offset,
                                    o.face_count,  o.spring_offset,   o.spring_count,
                                    o.tet_offset,  o.tet_count,       o.box_offset,
                                    o.box_count,   o.box_face_offset, o.box_face_count};
    for (std::uint32_t k = 0; k < 12; ++k)
      EXPECT_EQ(fields[k], probe(i, k)) << "field " << k;

    const gpu::BodyParams& p = out.body_params[i];
    EXPECT_EQ(p.carry_velocity, probe4(i, 0));
    EXPECT_EQ(p.damping, probef(i, 4));
    EXPECT_EQ(p.frozen, probef(i, 5));
    EXPECT_EQ(p.pad1, probef(i, 6));
    EXPECT_EQ(p.pad2, probef(i, 7));

    const gpu::Tetra& t = out.tets[i];
    EXPECT_EQ(t.a, probe(i, 0));
    EXPECT_EQ(t.b, probe(i, 1));
    EXPECT_EQ(t.c, probe(i, 2));
    EXPECT_EQ(t.d, probe(i, 3));
    EXPECT_EQ(t.rest_volume, probef(i, 4));
    EXPECT_EQ(t.stiffness, probef(i, 5));
    EXPECT_EQ(t.pad0, probef(i, 6));
    EXPECT_EQ(t.pad1, probef(i, 7));

    EXPECT_EQ(out.body_pairs[i].a, probe(i, 0));
    EXPECT_EQ(out.body_pairs[i].b, probe(i, 1));

    const gpu::FacePair& fp = out.face_pairs[i];
    EXPECT_EQ(fp.face_a, probe(i, 0));
    EXPECT_EQ(fp.face_b, probe(i, 1));
    EXPECT_EQ(fp.coplanar, probe(i, 2));
    EXPECT_EQ(fp.pad, probe(i, 3));
    EXPECT_EQ(fp.segment0, probe4(i, 4));
    EXPECT_EQ(fp.segment1, probe4(i, 8));

    const gpu::CollisionCounters& c = out.counters[i];
    EXPECT_EQ(c.face_pairs, probe(i, 0));
    EXPECT_EQ(c.box_pairs, probe(i, 1));
    EXPECT_EQ(c.colliding_faces, probe(i, 2));
    EXPECT_EQ(c.candidates, probe(i, 3));

    const gpu::BvhNode& n = out.bvh_nodes[i];
    EXPECT_EQ(n.left, probe(i, 0));
    EXPECT_EQ(n.right, probe(i, 1));
    EXPECT_EQ(n.parent, probe(i, 2));
    EXPECT_EQ(n.face, probe(i, 3));

    const gpu::BodyBvh& tree = out.body_bvhs[i];
    EXPECT_EQ(tree.root, probe(i, 0));
    EXPECT_EQ(tree.node_count, probe(i, 1));
    EXPECT_EQ(tree.depth, probe(i, 2));
    EXPECT_EQ(tree.pad, probe(i, 3));

    const gpu::MeshInfo& m = out.meshes[i];
    const std::uint32_t mesh_fields[] = {
        m.vertex_count,   m.face_offset,     m.face_count,      m.box_face_offset,
        m.box_face_count, m.position_offset, m.position_stride, m.pad};
    for (std::uint32_t k = 0; k < 8; ++k)
      EXPECT_EQ(mesh_fields[k], probe(i, k)) << "MeshInfo field " << k;

    const gpu::ContactPair& cp = out.contact_pairs[i];
    for (std::uint32_t k = 0; k < 4; ++k)
      EXPECT_EQ(cp.nodes[k], probe(i, k)) << "ContactPair node " << k;
    EXPECT_EQ(cp.kind, probe(i, 4));
    EXPECT_EQ(cp.thickness, probef(i, 5));
    EXPECT_EQ(cp.gap, probef(i, 6));
    EXPECT_EQ(cp.closing_speed, probef(i, 7));
    EXPECT_EQ(cp.side, probef(i, 8));
    EXPECT_EQ(cp.step_limit, probef(i, 9));
    EXPECT_EQ(cp.converge, probef(i, 10));
    EXPECT_EQ(cp.hold_depth, probef(i, 11));
  }
}

TEST_F(LayoutAgreementTest, BindingMacrosMatchTheBindingEnum) {
  const std::vector<std::uint32_t> expected = {
      gpu::kNodePosition,    gpu::kNodeVelocity,     gpu::kSpringEdge,    gpu::kNodeForce,
      gpu::kBoxInfo,         gpu::kCollisionResult,  gpu::kFaceNormal,    gpu::kFaceInfo,
      gpu::kObjectInfo,      gpu::kBoxFaceList,      gpu::kFacePair,      gpu::kBoxMask,
      gpu::kBodyParams,      gpu::kNodeBody,         gpu::kEdgeState,     gpu::kNodeEdgeOffset,
      gpu::kNodeEdgeTerm,    gpu::kTetInfo,          gpu::kCornerForce,   gpu::kNodeCornerOffset,
      gpu::kTetCornerSlot,   gpu::kFaceBoxes,        gpu::kBodyPair,      gpu::kCollisionCounters,
      gpu::kBoxRows,         gpu::kBvhNode,          gpu::kBvhBox,        gpu::kBodyBvh,
      gpu::kCandidatePair,   gpu::kContactPair,      gpu::kContactSlides, gpu::kNodeContactOffset,
      gpu::kNodeContactList, gpu::kNodeContactCount, gpu::kFrameStart,    gpu::kNodeMotion,
      gpu::kProjectionStart, gpu::kContactImpulse,   gpu::kNodeSlid,      gpu::kNodeGuard};
  ASSERT_EQ(expected.size(), kBindingCount);
  std::vector<std::uint32_t> bindings = run_layout_probe(1).bindings;
  ASSERT_EQ(bindings.size(), kBindingCount + kConstantCount);
  const std::vector<std::uint32_t> constants(bindings.begin() + kBindingCount, bindings.end());
  bindings.resize(kBindingCount);
  EXPECT_EQ(bindings, expected);
  EXPECT_EQ(constants[0], gpu::kLeafBoxesPerBody) << "LEAF_BOXES_PER_BODY";
  EXPECT_EQ(constants[1], gpu::kBvhInternal) << "BVH_INTERNAL";
  EXPECT_EQ(constants[2], collision::kBvhMaxDepth) << "BVH_MAX_DEPTH";
  EXPECT_EQ(constants[3], kDispatchArgsBinding) << "BINDING_DISPATCH_ARGS";
  EXPECT_EQ(constants[4], kBoxPairListBinding) << "BINDING_BOX_PAIR_LIST";
  EXPECT_EQ(constants[5], kBvhLevelsBinding) << "BINDING_BVH_LEVELS";
  EXPECT_EQ(constants[6], kTouchingPairsBinding) << "BINDING_TOUCHING_PAIRS";
  EXPECT_EQ(constants[7], kExpandArgsWord) << "DISPATCH_ARGS_EXPAND";
  EXPECT_EQ(constants[8], kTouchingCountWord) << "DISPATCH_ARGS_TOUCHING";
  EXPECT_EQ(constants[9], kNarrowArgsWord) << "DISPATCH_ARGS_NARROW";
  EXPECT_EQ(constants[10], kTraverseArgsWord) << "DISPATCH_ARGS_TRAVERSE";
  EXPECT_EQ(constants[11], kBvhLeavesBinding) << "BINDING_BVH_LEAVES";
  EXPECT_EQ(constants[12], gpu::kMeshInfo) << "BINDING_MESH_INFO";
  EXPECT_EQ(constants[13], kNonFiniteBinding) << "BINDING_NON_FINITE";
  EXPECT_EQ(constants[14], gpu::kContactVertexFace) << "CONTACT_VERTEX_FACE";
  EXPECT_EQ(constants[15], gpu::kContactEdgeEdge) << "CONTACT_EDGE_EDGE";
  EXPECT_EQ(constants[16], gpu::kContactUntangle) << "CONTACT_UNTANGLE";
  EXPECT_EQ(constants[17], gpu::kContactVolume) << "CONTACT_VOLUME";
  EXPECT_EQ(constants[18], kContactActingBinding) << "BINDING_CONTACT_ACTING";
  EXPECT_EQ(constants[19], kActingListBinding) << "BINDING_ACTING_LIST";
  EXPECT_EQ(constants[20], kNodeActiveSlotBinding) << "BINDING_NODE_ACTIVE_SLOT";
  EXPECT_EQ(constants[21], kTouchedNodeBinding) << "BINDING_TOUCHED_NODE";
  EXPECT_EQ(constants[22], kResponseStateBinding) << "BINDING_RESPONSE_STATE";
  EXPECT_EQ(constants[23], kActingContactsWord) << "RESPONSE_ACTING_CONTACTS";
  EXPECT_EQ(constants[24], kActingTotalWord) << "RESPONSE_ACTING_TOTAL";
  EXPECT_EQ(constants[25], kTouchedNodesWord) << "RESPONSE_TOUCHED_NODES";
  EXPECT_EQ(constants[26], kStrayFlagWord) << "RESPONSE_STRAY_FLAG";
  EXPECT_EQ(constants[27], kResidualFlagWord) << "RESPONSE_RESIDUAL_FLAG";
  EXPECT_EQ(constants[28], kResidualArgsWord) << "RESPONSE_RESIDUAL_ARGS";
  EXPECT_EQ(constants[29], kSlidePassArgsWord) << "RESPONSE_SLIDE_PASS_ARGS";
  EXPECT_EQ(constants[30], kSweepOrderBinding) << "BINDING_SWEEP_ORDER";
  EXPECT_EQ(constants[31], kSweepColoursBinding) << "BINDING_SWEEP_COLOURS";
}

}  // namespace
}  // namespace deformcd::gl
