#include "cpu/cpu_proximity.h"

#include <algorithm>

#include "core/collision/bvh.h"
#include "cpu/parallel_for.h"

namespace deformcd::cpu {

CpuProximity::CpuProximity(const collision::BvhUpkeep& trees, std::vector<gpu::BodyPair> mesh_pairs,
                           std::shared_ptr<Executor> executor)
    : trees_(trees),
      mesh_pairs_(std::move(mesh_pairs)),
      owners_(collision::primitive_owners(trees.faces())),
      executor_(std::move(executor)) {
  // Each vertex's faces (layout indices, ascending), for widen().
  const std::vector<gpu::Face>& faces = trees_.faces();
  vertex_first_ = collision::vertex_firsts(trees_.meshes());
  vertex_face_offset_.assign(vertex_first_.back() + 1u, 0u);
  for (const gpu::Face& f : faces)
    for (std::uint32_t k = 0; k < 3u; ++k)
      ++vertex_face_offset_[vertex_first_[f.body] + collision::face_corner(f, k) + 1u];
  for (std::size_t v = 1; v < vertex_face_offset_.size(); ++v)
    vertex_face_offset_[v] += vertex_face_offset_[v - 1u];
  vertex_faces_.resize(vertex_face_offset_.back());
  std::vector<std::uint32_t> cursor(vertex_face_offset_.begin(), vertex_face_offset_.end() - 1);
  for (std::uint32_t i = 0; i < faces.size(); ++i) {
    const gpu::Face& f = faces[i];
    for (std::uint32_t k = 0; k < 3u; ++k)
      vertex_faces_[cursor[vertex_first_[f.body] + collision::face_corner(f, k)]++] = i;
  }
}

void CpuProximity::refit(collision::VertexPositions positions, collision::VertexPositions motion,
                         collision::VertexReach reach) {
  // Every face swept once (each face pair it meets reads it), in parallel: pure per face.
  const std::vector<gpu::Face>& faces = trees_.faces();
  swept_.resize(faces.size());
  primitives_.resize(faces.size());
  primitives_state_.assign(faces.size(), kPrimitivesStale);
  parallel_for(faces.size(), [&](std::size_t i) {
    swept_[i] = collision::sweep_face(positions, motion, reach, faces[i]);
  });
  // Each leaf its face's swept box grown by the face's reach, each parent the union of its
  // children, in reverse preorder.
  const std::vector<gpu::BvhNode>& nodes = trees_.nodes();
  boxes_.resize(nodes.size());
  leaf_of_.resize(faces.size());
  for (const gpu::BodyBvh& tree : trees_.trees()) {
    for (std::uint32_t i = tree.root + tree.node_count; i-- > tree.root;) {
      const gpu::BvhNode& n = nodes[i];
      if (n.face != gpu::kBvhInternal) {
        boxes_[i] = swept_[n.face].box;
        leaf_of_[n.face] = i;
      } else {
        const gpu::Box& l = boxes_[n.left];
        const gpu::Box& r = boxes_[n.right];
        boxes_[i] = {glm::min(l.min, r.min), glm::max(l.max, r.max)};
      }
    }
  }
  boxes_generation_ = trees_.generation();
}

void CpuProximity::sweep_primitives_of_met_faces() {
  parallel_for(trees_.faces().size(), [&](std::size_t i) {
    if (primitives_state_[i] != kPrimitivesWanted) return;
    primitives_[i] = collision::sweep_primitives(swept_[i]);
    primitives_state_[i] = kPrimitivesSwept;
  });
}

std::vector<collision::ProximityCandidate> CpuProximity::find(
    collision::VertexPositions positions, collision::VertexPositions motion,
    collision::VertexReach reach, std::span<const std::uint32_t> mesh_pairs,
    std::vector<float>* distances) {
  std::vector<collision::ProximityCandidate> all;
  if (distances != nullptr) distances->clear();
  const std::vector<gpu::Face>& faces = trees_.faces();
  executor_->run([&] {
    refit(positions, motion, reach);
    // Fixed chunks of each mesh pair's first mesh's faces, each with its own lists, joined in
    // chunk order: the order does not depend on the schedule, and a face costs no allocation of
    // its own. First every chunk's face pairs (its faces in order, each one's in its traversal
    // order), marking the faces met; then the primitive boxes of those faces alone (most faces
    // meet none); then each chunk's candidates from its face pairs, in their order.
    constexpr std::size_t kChunk = 64;
    struct Chunk {
      std::uint32_t mesh_pair, first, end;  // faces [first, end) of the pair's mesh a
    };
    std::vector<Chunk> chunks;
    for (const std::uint32_t p : mesh_pairs) {
      const gpu::MeshInfo& mesh_a = trees_.meshes()[mesh_pairs_[p].a];
      for (std::uint32_t first = 0; first < mesh_a.face_count; first += kChunk) {
        chunks.push_back(
            {p, mesh_a.face_offset + first,
             mesh_a.face_offset + std::min<std::uint32_t>(first + kChunk, mesh_a.face_count)});
      }
    }
    std::vector<std::vector<std::array<std::uint32_t, 2>>> met(chunks.size());
    parallel_for(
        chunks.size(),
        [&](std::size_t c) {
          const Chunk& chunk = chunks[c];
          const gpu::BodyPair& pair = mesh_pairs_[chunk.mesh_pair];
          const gpu::BodyBvh& tree_b = trees_.tree(pair.b);
          const bool self = pair.a == pair.b;
          for (std::uint32_t index_a = chunk.first; index_a < chunk.end; ++index_a) {
            // Within one mesh each face pair once (a face with itself pairs only surface
            // neighbours, which the emit leaves out).
            collision::query_bvh(trees_.nodes().data(), boxes_.data(), tree_b.root,
                                 swept_[index_a].box, [&](std::uint32_t index_b) {
                                   if (self && index_b <= index_a) return;
                                   met[c].push_back({index_a, index_b});
                                   want_primitives(index_a);
                                   want_primitives(index_b);
                                 });
          }
        },
        1);
    sweep_primitives_of_met_faces();
    std::vector<std::vector<collision::ProximityCandidate>> per_chunk(chunks.size());
    std::vector<std::vector<float>> per_chunk_distance(chunks.size());
    parallel_for(
        chunks.size(),
        [&](std::size_t c) {
          auto& out = per_chunk[c];
          auto& out_distance = per_chunk_distance[c];
          for (const auto& [a, b] : met[c]) {
            collision::emit_face_pair_candidates(
                faces[a], swept_[a], primitives_[a], a, owners_[a], faces[b], swept_[b],
                primitives_[b], b, owners_[b],
                [&](const collision::ProximityCandidate& candidate, float distance) {
                  out.push_back(candidate);
                  out_distance.push_back(distance);
                });
          }
        },
        1);
    std::size_t total = 0;
    for (const auto& list : per_chunk)
      total += list.size();
    all.reserve(total);
    for (const auto& list : per_chunk)
      all.insert(all.end(), list.begin(), list.end());
    if (distances != nullptr) {
      distances->reserve(total);
      for (const auto& list : per_chunk_distance)
        distances->insert(distances->end(), list.begin(), list.end());
    }
  });
  return all;
}

std::vector<collision::ProximityCandidate> CpuProximity::widen(
    collision::VertexPositions positions, collision::VertexPositions motion,
    collision::VertexReach reach, std::span<const std::uint32_t> mesh_pairs,
    std::span<const std::array<std::uint32_t, 2>> widened, std::vector<float>& distances) {
  std::vector<collision::ProximityCandidate> out;
  distances.clear();
  const std::vector<gpu::Face>& faces_of = trees_.faces();
  executor_->run([&] {
    if (boxes_generation_ != trees_.generation()) refit(positions, motion, reach);
    // The faces with a widened corner: their leaves swept again with the raised reaches, then
    // every tree's parents in reverse preorder (unions only).
    std::vector<std::uint8_t> is_widened(vertex_first_.back(), 0u);
    std::vector<std::uint32_t> faces;
    for (const auto& [mesh, vertex] : widened) {
      const std::uint32_t v = vertex_first_[mesh] + vertex;
      is_widened[v] = 1u;
      faces.insert(faces.end(), vertex_faces_.begin() + vertex_face_offset_[v],
                   vertex_faces_.begin() + vertex_face_offset_[v + 1u]);
    }
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    const std::vector<gpu::BvhNode>& nodes = trees_.nodes();
    for (const std::uint32_t face : faces) {
      swept_[face] = collision::sweep_face(positions, motion, reach, faces_of[face]);
      primitives_state_[face] = kPrimitivesStale;
      boxes_[leaf_of_[face]] = swept_[face].box;
    }
    for (const gpu::BodyBvh& tree : trees_.trees()) {
      for (std::uint32_t i = tree.root + tree.node_count; i-- > tree.root;) {
        const gpu::BvhNode& n = nodes[i];
        if (n.face != gpu::kBvhInternal) continue;
        const gpu::Box& l = boxes_[n.left];
        const gpu::Box& r = boxes_[n.right];
        boxes_[i] = {glm::min(l.min, r.min), glm::max(l.max, r.max)};
      }
    }
    // Each widened face's face pairs, with the pair's faces as find() orders them (the first
    // mesh's face first; within one mesh the lower face first), sorted: the order does not
    // depend on the trees (which the GL and CPU backends rebuild on schedules of their own). A
    // pair of two widened faces is met from both: each keeps the candidates it is responsible
    // for (below), so that every candidate comes once.
    std::vector<std::uint8_t> face_widened(faces_of.size(), 0u);
    for (const std::uint32_t face : faces)
      face_widened[face] = 1u;
    struct FacePair {
      std::uint32_t mesh_pair, a, b;  // the pair's faces
      std::uint32_t from;             // the widened face that met it
      // clang-tidy's modernize-use-nullptr flags a defaulted <=> (the literal 0 the synthesized
      // comparison compares against): a false positive, as in proximity.h.
      // NOLINTNEXTLINE(modernize-use-nullptr)
      auto operator<=>(const FacePair&) const = default;
    };
    std::vector<FacePair> pairs;
    for (const std::uint32_t p : mesh_pairs) {
      const gpu::BodyPair& mp = mesh_pairs_[p];
      for (const std::uint32_t face : faces) {
        const std::uint32_t mesh = faces_of[face].body;
        if (mesh != mp.a && mesh != mp.b) continue;
        const bool first = mesh == mp.a;
        collision::query_bvh(
            nodes.data(), boxes_.data(), trees_.tree(first ? mp.b : mp.a).root,
            boxes_[leaf_of_[face]], [&](std::uint32_t other) {
              if (mp.a == mp.b) {
                if (other != face)
                  pairs.push_back({p, std::min(face, other), std::max(face, other), face});
              } else {
                pairs.push_back({p, first ? face : other, first ? other : face, face});
              }
            });
      }
    }
    std::sort(pairs.begin(), pairs.end());
    for (const FacePair& fp : pairs) {
      want_primitives(fp.a);
      want_primitives(fp.b);
    }
    sweep_primitives_of_met_faces();
    const auto widened_vertex = [&](std::uint32_t mesh, std::uint32_t v) {
      return is_widened[vertex_first_[mesh] + v] != 0u;
    };
    for (const FacePair& fp : pairs) {
      // A candidate involves a widened vertex when its vertex (or an edge's end) is one, or its
      // face has one as a corner. The widened face that owns such a vertex or edge emits it; a
      // candidate whose widened part is only the face (or the second edge) is emitted from that.
      const auto responsible = [&](const collision::ProximityCandidate& c) {
        if (c.kind == gpu::kContactVertexFace) {
          if (widened_vertex(c.mesh_a, c.vertices[0])) return fp.from != c.face_b;
          return face_widened[c.face_b] != 0u && fp.from == c.face_b;
        }
        if (widened_vertex(c.mesh_a, c.vertices[0]) || widened_vertex(c.mesh_a, c.vertices[1]))
          return fp.from == fp.a;
        return (widened_vertex(c.mesh_b, c.vertices[2]) ||
                widened_vertex(c.mesh_b, c.vertices[3])) &&
               fp.from == fp.b;
      };
      collision::emit_face_pair_candidates(
          faces_of[fp.a], swept_[fp.a], primitives_[fp.a], fp.a, owners_[fp.a], faces_of[fp.b],
          swept_[fp.b], primitives_[fp.b], fp.b, owners_[fp.b],
          [&](const collision::ProximityCandidate& c, float distance) {
            out.push_back(c);
            distances.push_back(distance);
          },
          responsible);
    }
  });
  return out;
}

}  // namespace deformcd::cpu
