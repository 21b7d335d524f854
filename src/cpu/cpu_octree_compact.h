#pragma once
// The `octree-compact` broad phase (beyond the paper): the paper's 64 leaf boxes per body and
// box-pair mask, but the triangle tests run over the face pairs of the overlapping box pairs
// only, instead of over all N' x M' row pairs with the mask read per pair. Next to `octree`, it
// shows how much of a hierarchy's gain comes from compaction alone.

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "cpu/cpu_narrow_phase.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::cpu {

// The leaf-box lists of every body (SimulationState::box_faces, face_boxes, box_rows).
struct LeafBoxRows {
  const gpu::BoxFace* box_faces;  // rows, box by box
  const glm::uvec2* face_boxes;   // per global face: the leaf boxes listing it
  const glm::uvec2* box_rows;     // per global leaf box: first row, row count
};

class OctreeCompactPass {
 public:
  // Tests body a's and body b's faces listed under each overlapping leaf-box pair (i, j) of
  // `mask` (64 x 64, 1 where box i of a overlaps box j of b). A face pair listed under several
  // overlapping box pairs is tested under the first one only (collision::is_first_box_pair), so
  // each pair is tested, and reported, once.
  void run(const gpu::BodyPair& pair, const std::vector<std::int32_t>& mask,
           const LeafBoxRows& lists, const NarrowPhase& narrow, PairCollector& out);

 private:
  std::vector<glm::uvec2> overlapping_;  // (i, j) per overlapping box pair; kept between passes
};

}  // namespace deformcd::cpu
