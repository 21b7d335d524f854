#include "cpu/cpu_collision.h"

#include <algorithm>
#include <tuple>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include "core/collision/broad_phase.h"
#include "cpu/parallel_for.h"
#include "deformcd/error.h"

namespace deformcd::cpu {

namespace {

constexpr std::uint32_t kBoxes = gpu::kLeafBoxesPerBody;

// Rows of a narrow-phase sweep per task: each row runs over all of the other body's rows.
constexpr std::size_t kRowGrain = 16;

// Faces per task of the per-face flag loops (a store or a compare each).
constexpr std::size_t kFaceGrain = 16384;

// Up to this many pairs, one thread sorts them by radix; more go to tbb::parallel_sort.
constexpr std::size_t kRadixSortPairs = 16384;

// Sorts `pairs` by (face_a, face_b), which are unique, by least significant digit first radix
// sort over 8-bit digits of the 64-bit key face_a x 2^32 + face_b, skipping the digits every key
// shares (with fewer than 2^16 faces, 4 of the 8). The order is the comparison sort's. On
// bench_peers' phase 1 (about 400 pairs a pass) std::sort of the 48-byte pairs was 2.5 % of a
// one-thread bvh pass. `scratch` is a buffer of the pass's, kept between passes.
void radix_sort_pairs(std::vector<gpu::FacePair>& pairs, std::vector<gpu::FacePair>& scratch) {
  const auto key = [](const gpu::FacePair& p) {
    return std::uint64_t{p.face_a} << 32u | std::uint64_t{p.face_b};
  };
  scratch.resize(pairs.size());
  for (unsigned shift = 0; shift < 64; shift += 8) {
    std::size_t count[256] = {};
    for (const gpu::FacePair& p : pairs)
      ++count[(key(p) >> shift) & 0xFFu];
    if (count[(key(pairs.front()) >> shift) & 0xFFu] == pairs.size()) continue;  // one digit
    std::size_t offset = 0;
    for (std::size_t& c : count) {
      const std::size_t n = c;
      c = offset;
      offset += n;
    }
    for (const gpu::FacePair& p : pairs)
      scratch[count[(key(p) >> shift) & 0xFFu]++] = p;
    pairs.swap(scratch);
  }
}

}  // namespace

CpuCollision::CpuCollision(std::shared_ptr<Executor> executor) : executor_(std::move(executor)) {}

void CpuCollision::upload(const collision::CollisionData& data) {
  // The trees are fitted to the positions on upload.
  if (vertices_.size() != data.meshes.size()) {
    throw Error("CPU collision: positions are set for " + std::to_string(vertices_.size()) +
                " meshes, the data has " + std::to_string(data.meshes.size()) +
                " (set them before uploading)");
  }
  faces_ = data.faces;
  meshes_ = data.meshes;
  box_faces_ = data.box_faces;
  face_boxes_ = data.face_boxes;
  box_rows_ = data.box_rows;
  mesh_pairs_ = data.mesh_pairs;
  boxes_.assign(box_rows_.size(), collision::empty_box());
  mask_.assign(std::size_t{kBoxes} * kBoxes, -1);
  flags_.assign(faces_.size(), 0u);
  geometry_.reset(faces_.size());
  pairs_.clear();
  counters_ = {};
  proximity_.reset();  // its per-face tables are the old faces'
  executor_->run([&] { bvh_.upload(data, vertices_.data()); });
}

void CpuCollision::set_positions(const std::vector<collision::PositionSource>& sources) {
  std::vector<collision::MeshVertices> vertices;
  std::vector<std::uint32_t> counts;
  for (std::size_t m = 0; m < sources.size(); ++m) {
    const collision::PositionSource& s = sources[m];
    if (s.kind == collision::PositionSource::Kind::kNone) {  // not set yet
      vertices.push_back({nullptr, 0u});
      counts.push_back(s.vertex_count);
      continue;
    }
    if (s.kind != collision::PositionSource::Kind::kHost || s.host == nullptr ||
        s.stride_bytes % sizeof(float) != 0) {
      throw Error("CPU collision: mesh " + std::to_string(m) +
                  " needs positions in host memory with a stride that is a multiple of 4 bytes");
    }
    vertices.push_back({s.host, static_cast<std::uint32_t>(s.stride_bytes / sizeof(float))});
    counts.push_back(s.vertex_count);
  }
  vertices_ = std::move(vertices);
  vertex_counts_ = std::move(counts);
}

std::vector<glm::vec3> CpuCollision::read_positions(std::uint32_t mesh) {
  if (mesh >= vertices_.size()) {
    throw Error("CPU collision: no positions for mesh " + std::to_string(mesh));
  }
  std::vector<glm::vec3> out(vertex_counts_[mesh]);
  for (std::uint32_t i = 0; i < out.size(); ++i)
    out[i] = collision::vertex_position(vertices_.data(), mesh, i);
  return out;
}

void CpuCollision::detect(BroadPhase method) {
  if (vertices_.size() != meshes_.size()) {
    throw Error("CPU collision: upload the data and set the positions before detecting");
  }
  executor_->run([&] { run(method); });
}

std::vector<collision::ProximityCandidate> CpuCollision::find_proximity(
    const collision::ProximityQuery& query, std::vector<float>& distances) {
  if (vertices_.size() != meshes_.size()) {
    throw Error("CPU collision: upload the data and set the positions before a proximity search");
  }
  // The trees each searched pair's faces query: its second mesh's.
  std::vector<std::uint8_t> queried(meshes_.size(), 0u);
  for (const std::uint32_t p : query.mesh_pairs)
    queried[mesh_pairs_[p].b] = 1u;
  executor_->run([&] { bvh_.fit_trees(query.positions, queried); });
  if (!proximity_)
    proximity_ = std::make_unique<CpuProximity>(bvh_.trees().upkeep(), mesh_pairs_, executor_);
  return proximity_->find(query.positions, query.motion, query.reach, query.mesh_pairs, &distances);
}

std::vector<collision::ProximityCandidate> CpuCollision::widen_proximity(
    const collision::ProximityQuery& query, std::span<const std::array<std::uint32_t, 2>> widened,
    std::vector<float>& distances) {
  if (!proximity_) throw Error("CPU collision: widen_proximity before a proximity search");
  return proximity_->widen(query.positions, query.motion, query.reach, query.mesh_pairs, widened,
                           distances);
}

void CpuCollision::run(BroadPhase method) {
  // Per face, in parallel: at 50,000 faces per body the serial fill and count below were a few
  // % of a bvh pass, which two threads could not share.
  parallel_for(
      flags_.size(), [&](std::size_t f) { flags_[f] = 0u; }, kFaceGrain);
  pairs_.clear();
  counters_ = {};
  geometry_.begin_pass(executor_->threads() > 1);
  const NarrowPhase narrow{vertices_.data(), faces_.data(), flags_.data(), &geometry_,
                           method == BroadPhase::kBvh};
  switch (method) {
    case BroadPhase::kNone:
      return;
    case BroadPhase::kBrute:
      for (const gpu::BodyPair& pair : mesh_pairs_)
        brute_pair(pair, narrow);
      break;
    case BroadPhase::kOctree:
    case BroadPhase::kOctreeCompact: {
      update_boxes();
      const LeafBoxRows lists{box_faces_.data(), face_boxes_.data(), box_rows_.data()};
      for (const gpu::BodyPair& pair : mesh_pairs_) {
        update_box_mask(pair);
        if (method == BroadPhase::kOctree) {
          octree_pair(pair, narrow);
        } else {
          octree_compact_.run(pair, mask_, lists, narrow, collector_);
        }
      }
      break;
    }
    case BroadPhase::kBvh:
      bvh_.run(vertices_.data(), narrow, collector_);
      break;
  }
  counters_.candidates = saturate_u32(collector_.gather(pairs_));
  // Threads append in any order; sorting makes the raw output one list whatever the schedule
  // (each face pair is found once, so the order is total).
  if (pairs_.size() <= kRadixSortPairs) {
    if (!pairs_.empty()) radix_sort_pairs(pairs_, sort_scratch_);
  } else {
    tbb::parallel_sort(pairs_.begin(), pairs_.end(),
                       [](const gpu::FacePair& x, const gpu::FacePair& y) {
                         return std::tie(x.face_a, x.face_b) < std::tie(y.face_a, y.face_b);
                       });
  }
  counters_.face_pairs = static_cast<std::uint32_t>(pairs_.size());
  // An integer sum: the same in any order.
  const std::uint32_t colliding = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, flags_.size(), kFaceGrain), 0u,
      [&](const tbb::blocked_range<std::size_t>& r, std::uint32_t sum) {
        for (std::size_t f = r.begin(); f != r.end(); ++f)
          sum += flags_[f] != 0u ? 1u : 0u;
        return sum;
      },
      [](std::uint32_t x, std::uint32_t y) { return x + y; });
  counters_.colliding_faces = colliding;
}

// BBUpdate (Algorithm 1): each leaf box from its listed faces' current vertices.
void CpuCollision::update_boxes() {
  const collision::VertexPositions p = vertices_.data();
  parallel_for(
      box_rows_.size(),
      [&](std::size_t box) {
        gpu::Box b = collision::empty_box();
        const glm::uvec2 rows = box_rows_[box];
        for (std::uint32_t r = rows.x; r < rows.x + rows.y; ++r) {
          const gpu::Face& f = faces_[box_faces_[r].face];
          collision::grow_box(b, collision::vertex_position(p, f.body, f.a));
          collision::grow_box(b, collision::vertex_position(p, f.body, f.b));
          collision::grow_box(b, collision::vertex_position(p, f.body, f.c));
        }
        boxes_[box] = b;
      },
      64);
}

void CpuCollision::update_box_mask(const gpu::BodyPair& pair) {
  const std::uint32_t box_a = pair.a * kBoxes;
  const std::uint32_t box_b = pair.b * kBoxes;
  for (std::uint32_t i = 0; i < kBoxes; ++i) {
    for (std::uint32_t j = 0; j < kBoxes; ++j) {
      const bool overlap = collision::boxes_overlap(boxes_[box_a + i], boxes_[box_b + j]);
      mask_[i * kBoxes + j] = overlap ? 1 : 0;
      counters_.box_pairs += overlap ? 1u : 0u;
    }
  }
}

// The N' x M' sweep over the two bodies' BoundingBox Face List rows (Algorithm 3), skipping
// rows whose boxes do not overlap.
void CpuCollision::octree_pair(const gpu::BodyPair& pair, const NarrowPhase& narrow) {
  const gpu::MeshInfo& a = meshes_[pair.a];
  const gpu::MeshInfo& b = meshes_[pair.b];
  const auto overlap = [&](std::uint32_t i, std::uint32_t j) { return mask_[i * kBoxes + j] == 1; };
  parallel_for(
      a.box_face_count,
      [&](std::size_t x) {
        ThreadPairs& local = collector_.local();
        const gpu::BoxFace row_a = box_faces_[a.box_face_offset + x];
        for (std::uint32_t y = 0; y < b.box_face_count; ++y) {
          const gpu::BoxFace row_b = box_faces_[b.box_face_offset + y];
          if (mask_[row_a.box * kBoxes + row_b.box] != 1) continue;
          if (!collision::is_first_box_pair(face_boxes_[row_a.face], face_boxes_[row_b.face],
                                            row_a.box, row_b.box, overlap))
            continue;
          narrow.test(row_a.face, row_b.face, local);
        }
      },
      kRowGrain);
}

// The paper's baseline: every face of mesh a against every face of mesh b (for a mesh against
// itself, the narrow phase keeps the pairs x < y).
void CpuCollision::brute_pair(const gpu::BodyPair& pair, const NarrowPhase& narrow) {
  const gpu::MeshInfo& a = meshes_[pair.a];
  const gpu::MeshInfo& b = meshes_[pair.b];
  parallel_for(
      a.face_count,
      [&](std::size_t x) {
        ThreadPairs& local = collector_.local();
        const auto face_a = static_cast<std::uint32_t>(a.face_offset + x);
        for (std::uint32_t y = 0; y < b.face_count; ++y)
          narrow.test(face_a, b.face_offset + y, local);
      },
      kRowGrain);
}

}  // namespace deformcd::cpu
