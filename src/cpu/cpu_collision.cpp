#include "cpu_collision.h"

#include <atomic>

#include "core/collision/broad_phase.h"
#include "core/collision/tri_tri_intersection.h"
#include "deformcd/error.h"
#include "parallel_for.h"

namespace deformcd::cpu {

namespace {

constexpr std::uint32_t kBoxes = gpu::kLeafBoxesPerBody;

// Rows of a narrow-phase sweep per task: each row runs over all of the other body's rows.
constexpr std::size_t kRowGrain = 16;

}  // namespace

void CpuCollision::upload(const WorldState& state) {
  faces_ = state.faces;
  objects_ = state.objects;
  box_faces_ = state.box_faces;
  face_boxes_ = state.face_boxes;
  box_rows_ = state.box_rows;
  body_pairs_ = state.body_pairs;
  boxes_.assign(box_rows_.size(), collision::empty_box());
  mask_.assign(std::size_t{kBoxes} * kBoxes, -1);
  flags_.assign(faces_.size(), 0u);
  pairs_.clear();
  counters_ = {};
}

void CpuCollision::detect(BroadPhase method) {
  if (simulation_.state().positions.empty() && !faces_.empty()) {
    throw Error("CPU collision: the simulation holds no positions (upload it first)");
  }
  std::fill(flags_.begin(), flags_.end(), 0u);
  pairs_.clear();
  counters_ = {};
  if (method == BroadPhase::kNone) return;
  if (method == BroadPhase::kOctree) update_boxes();
  for (const gpu::BodyPair& pair : body_pairs_) {
    if (method == BroadPhase::kOctree) {
      octree_pair(pair);
    } else {
      brute_pair(pair);
    }
  }
  counters_.face_pairs = static_cast<std::uint32_t>(pairs_.size());
  std::uint32_t colliding = 0;
  for (std::uint32_t f : flags_)
    colliding += f != 0u ? 1u : 0u;
  counters_.colliding_faces = colliding;
}

// BBUpdate (Algorithm 1): each leaf box from its listed faces' current vertices.
void CpuCollision::update_boxes() {
  const std::vector<glm::vec4>& p = simulation_.state().positions;
  parallel_for(
      box_rows_.size(),
      [&](std::size_t box) {
        gpu::Box b = collision::empty_box();
        const glm::uvec2 rows = box_rows_[box];
        for (std::uint32_t r = rows.x; r < rows.x + rows.y; ++r) {
          const gpu::Face& f = faces_[box_faces_[r].face];
          collision::grow_box(b, glm::vec3(p[f.a]));
          collision::grow_box(b, glm::vec3(p[f.b]));
          collision::grow_box(b, glm::vec3(p[f.c]));
        }
        boxes_[box] = b;
      },
      64);
}

void CpuCollision::test_faces(std::uint32_t face_a, std::uint32_t face_b,
                              std::vector<gpu::FacePair>& out) {
  const std::vector<glm::vec4>& p = simulation_.state().positions;
  const gpu::Face& fa = faces_[face_a];
  const gpu::Face& fb = faces_[face_b];
  const glm::vec3 ta[3] = {glm::vec3(p[fa.a]), glm::vec3(p[fa.b]), glm::vec3(p[fa.c])};
  const glm::vec3 tb[3] = {glm::vec3(p[fb.a]), glm::vec3(p[fb.b]), glm::vec3(p[fb.c])};
  const collision::TriTriResult hit = collision::tri_tri_intersect(ta, tb);
  if (!hit.intersect) return;
  // Several threads may flag one face; the value written is the same.
  std::atomic_ref<std::uint32_t>(flags_[face_a]).store(1u, std::memory_order_relaxed);
  std::atomic_ref<std::uint32_t>(flags_[face_b]).store(1u, std::memory_order_relaxed);
  out.push_back({face_a, face_b, hit.coplanar ? 1u : 0u, 0u, glm::vec4(hit.segment[0], 0.0f),
                 glm::vec4(hit.segment[1], 0.0f)});
}

// Results are gathered per row, then appended in row order: the output does not depend on the
// thread schedule.
void CpuCollision::collect(std::vector<std::vector<gpu::FacePair>>& per_row) {
  for (std::vector<gpu::FacePair>& row : per_row) {
    pairs_.insert(pairs_.end(), row.begin(), row.end());
  }
}

// BBCollision (Algorithm 2) into the 64 x 64 mask, then the N' x M' sweep over the two bodies'
// BoundingBox Face List rows (Algorithm 3), skipping rows whose boxes do not overlap.
void CpuCollision::octree_pair(const gpu::BodyPair& pair) {
  const std::uint32_t box_a = pair.a * kBoxes;
  const std::uint32_t box_b = pair.b * kBoxes;
  for (std::uint32_t i = 0; i < kBoxes; ++i) {
    for (std::uint32_t j = 0; j < kBoxes; ++j) {
      const bool overlap = collision::boxes_overlap(boxes_[box_a + i], boxes_[box_b + j]);
      mask_[i * kBoxes + j] = overlap ? 1 : 0;
      counters_.box_pairs += overlap ? 1u : 0u;
    }
  }
  const gpu::ObjectInfo& a = objects_[pair.a];
  const gpu::ObjectInfo& b = objects_[pair.b];
  const auto overlap = [&](std::uint32_t i, std::uint32_t j) { return mask_[i * kBoxes + j] == 1; };
  std::vector<std::vector<gpu::FacePair>> per_row(a.box_face_count);
  parallel_for(
      a.box_face_count,
      [&](std::size_t x) {
        const gpu::BoxFace row_a = box_faces_[a.box_face_offset + x];
        for (std::uint32_t y = 0; y < b.box_face_count; ++y) {
          const gpu::BoxFace row_b = box_faces_[b.box_face_offset + y];
          if (mask_[row_a.box * kBoxes + row_b.box] != 1) continue;
          if (!collision::is_first_box_pair(face_boxes_[row_a.face], face_boxes_[row_b.face],
                                            row_a.box, row_b.box, overlap))
            continue;
          test_faces(row_a.face, row_b.face, per_row[x]);
        }
      },
      kRowGrain);
  collect(per_row);
}

// The paper's baseline: every face of body a against every face of body b.
void CpuCollision::brute_pair(const gpu::BodyPair& pair) {
  const gpu::ObjectInfo& a = objects_[pair.a];
  const gpu::ObjectInfo& b = objects_[pair.b];
  std::vector<std::vector<gpu::FacePair>> per_row(a.face_count);
  parallel_for(
      a.face_count,
      [&](std::size_t x) {
        const auto face_a = static_cast<std::uint32_t>(a.face_offset + x);
        for (std::uint32_t y = 0; y < b.face_count; ++y) {
          test_faces(face_a, b.face_offset + y, per_row[x]);
        }
      },
      kRowGrain);
  collect(per_row);
}

}  // namespace deformcd::cpu
