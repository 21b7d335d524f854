#include "cpu/cpu_octree_compact.h"

#include "core/collision/broad_phase.h"
#include "cpu/parallel_for.h"

namespace deformcd::cpu {

namespace {
constexpr std::uint32_t kBoxes = gpu::kLeafBoxesPerBody;
}  // namespace

void OctreeCompactPass::run(const gpu::BodyPair& pair, const std::vector<std::int32_t>& mask,
                            const LeafBoxRows& lists, const NarrowPhase& narrow,
                            PairCollector& out) {
  overlapping_.clear();
  for (std::uint32_t i = 0; i < kBoxes; ++i) {
    for (std::uint32_t j = 0; j < kBoxes; ++j) {
      if (mask[i * kBoxes + j] == 1) overlapping_.emplace_back(i, j);
    }
  }
  const auto overlap = [&](std::uint32_t i, std::uint32_t j) { return mask[i * kBoxes + j] == 1; };
  // One task per box pair: their sizes vary (a box holds 0 to a few hundred faces), and work
  // stealing over single box pairs balances them; a pass has tens to thousands of them.
  parallel_for(
      overlapping_.size(),
      [&](std::size_t k) {
        const std::uint32_t box_a = overlapping_[k].x;
        const std::uint32_t box_b = overlapping_[k].y;
        const glm::uvec2 rows_a = lists.box_rows[pair.a * kBoxes + box_a];
        const glm::uvec2 rows_b = lists.box_rows[pair.b * kBoxes + box_b];
        ThreadPairs& local = out.local();
        for (std::uint32_t x = rows_a.x; x < rows_a.x + rows_a.y; ++x) {
          const std::uint32_t face_a = lists.box_faces[x].face;
          const glm::uvec2 boxes_a = lists.face_boxes[face_a];
          for (std::uint32_t y = rows_b.x; y < rows_b.x + rows_b.y; ++y) {
            const std::uint32_t face_b = lists.box_faces[y].face;
            if (!collision::is_first_box_pair(boxes_a, lists.face_boxes[face_b], box_a, box_b,
                                              overlap))
              continue;
            narrow.test(face_a, face_b, local);
          }
        }
      },
      1);
}

}  // namespace deformcd::cpu
