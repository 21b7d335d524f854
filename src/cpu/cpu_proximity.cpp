#include "cpu/cpu_proximity.h"

#include <algorithm>
#include <functional>

#include "core/collision/bvh.h"
#include "cpu/cpu_bvh_pair_traversal.h"
#include "cpu/parallel_for.h"

namespace deformcd::cpu {

namespace {

// Calls emit_pair(i, push) for i in [0, count) in fixed chunks of `chunk`, in parallel, each
// chunk's push(candidate, distance) into lists of its own, and appends the lists in chunk
// order to `out` and `distances` (when not null): the same result on any thread count.
template <class EmitPair>
void emit_in_chunks(std::size_t count, std::size_t chunk, const EmitPair& emit_pair,
                    std::vector<collision::ProximityCandidate>& out,
                    std::vector<float>* distances) {
  const std::size_t chunks = (count + chunk - 1u) / chunk;
  std::vector<std::vector<collision::ProximityCandidate>> per_chunk(chunks);
  std::vector<std::vector<float>> per_chunk_distance(chunks);
  parallel_for(
      chunks,
      [&](std::size_t c) {
        const auto push = [&](const collision::ProximityCandidate& candidate, float distance) {
          per_chunk[c].push_back(candidate);
          per_chunk_distance[c].push_back(distance);
        };
        for (std::size_t i = c * chunk; i < std::min(count, (c + 1u) * chunk); ++i)
          emit_pair(i, push);
      },
      1);
  std::size_t total = out.size();
  for (const auto& list : per_chunk)
    total += list.size();
  out.reserve(total);
  for (const auto& list : per_chunk)
    out.insert(out.end(), list.begin(), list.end());
  if (distances != nullptr) {
    distances->reserve(total);
    for (const auto& list : per_chunk_distance)
      distances->insert(distances->end(), list.begin(), list.end());
  }
}

}  // namespace

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
  // children, in reverse preorder; the trees (one per mesh, their nodes, faces and records
  // their own) in parallel.
  const std::vector<gpu::BvhNode>& nodes = trees_.nodes();
  if (records_generation_ != trees_.generation()) make_records();
  boxes_.resize(nodes.size());
  leaf_of_.resize(faces.size());
  const std::vector<gpu::BodyBvh>& trees = trees_.trees();
  parallel_for(
      trees.size(),
      [&](std::size_t t) {
        const gpu::BodyBvh& tree = trees[t];
        for (std::uint32_t i = tree.root + tree.node_count; i-- > tree.root;) {
          const gpu::BvhNode& n = nodes[i];
          if (n.face != gpu::kBvhInternal) {
            boxes_[i] = swept_[n.face].box;
            leaf_of_[n.face] = i;
          } else {
            const gpu::Box& l = boxes_[n.left];
            const gpu::Box& r = boxes_[n.right];
            boxes_[i] = {glm::min(l.min, r.min), glm::max(l.max, r.max)};
            ChildBoxes& record = records_[record_of_[i]];
            set_child_box(record, 0u, glm::vec3(l.min), glm::vec3(l.max));
            set_child_box(record, 1u, glm::vec3(r.min), glm::vec3(r.max));
          }
        }
      },
      1);
  boxes_generation_ = trees_.generation();
}

void CpuProximity::make_records() {
  make_child_records(trees_.nodes(), trees_.faces().size(), records_, record_of_);
  records_generation_ = trees_.generation();
}

std::vector<std::array<std::uint32_t, 2>> CpuProximity::met_face_pairs(
    std::span<const std::uint32_t> mesh_pairs) {
  // Each mesh pair's trees descended together, cut into a fixed number of independent node
  // pairs (expand_frontier: the cut does not depend on the thread count), each traversed by one
  // task into a list of its own. A face pair is recorded under its bucket (the mesh pair's, then
  // its first face's), with its second face.
  constexpr std::size_t kPieces = 64;
  struct Piece {
    std::uint32_t slot;  // index into mesh_pairs
    NodePair nodes;
  };
  std::vector<Piece> pieces;
  std::vector<std::uint32_t> bucket_base(mesh_pairs.size() + 1u, 0u);
  std::vector<NodePair> frontier, scratch;
  const gpu::BvhNode* nodes = trees_.nodes().data();
  for (std::uint32_t slot = 0; slot < mesh_pairs.size(); ++slot) {
    const gpu::BodyPair& pair = mesh_pairs_[mesh_pairs[slot]];
    bucket_base[slot + 1u] = bucket_base[slot] + trees_.meshes()[pair.a].face_count;
    const std::uint32_t root_a = trees_.tree(pair.a).root, root_b = trees_.tree(pair.b).root;
    if (!collision::boxes_overlap(boxes_[root_a], boxes_[root_b])) continue;
    frontier.assign(1, NodePair{root_a, root_b});
    expand_frontier(nodes, boxes_.data(), pair.a == pair.b, kPieces, frontier, scratch);
    for (const NodePair& p : frontier)
      pieces.push_back({slot, p});
  }
  struct Met {
    std::uint32_t bucket, face_a, face_b;
  };
  std::vector<std::vector<Met>> met(pieces.size());
  const TraversalTrees t{nodes, boxes_.data(), records_.data(), record_of_.data()};
  parallel_for(
      pieces.size(),
      [&](std::size_t i) {
        const Piece& piece = pieces[i];
        const gpu::BodyPair& pair = mesh_pairs_[mesh_pairs[piece.slot]];
        const bool self = pair.a == pair.b;
        const std::uint32_t base = bucket_base[piece.slot] - trees_.meshes()[pair.a].face_offset;
        traverse_node_pair(t, self, piece.nodes, [&](std::uint32_t a, std::uint32_t b) {
          if (self && b < a) std::swap(a, b);
          met[i].push_back({base + a, a, b});
        });
      },
      1);
  // A counting sort by bucket (the order of the mesh pairs and their first faces), then each
  // bucket by the second face's leaf: one query per first face meets its leaves in preorder.
  // (Counted and scattered in parallel with integer atomics, the list was the same but the
  // atomics cost one thread more than two threads saved:
  // docs/notes/2026-12-08-serial-host-work.md.)
  std::vector<std::uint32_t> offset(bucket_base.back() + 1u, 0u);
  for (const std::vector<Met>& list : met)
    for (const Met& m : list)
      ++offset[m.bucket + 1u];
  for (std::size_t b = 1; b < offset.size(); ++b)
    offset[b] += offset[b - 1u];
  std::vector<std::array<std::uint32_t, 2>> sorted(offset.back());
  std::vector<std::uint32_t> cursor(offset.begin(), offset.end() - 1);
  for (const std::vector<Met>& list : met)
    for (const Met& m : list)
      sorted[cursor[m.bucket]++] = {m.face_a, m.face_b};
  parallel_for(
      offset.size() - 1u,
      [&](std::size_t b) {
        std::sort(
            sorted.begin() + offset[b], sorted.begin() + offset[b + 1u],
            [&](const std::array<std::uint32_t, 2>& x, const std::array<std::uint32_t, 2>& y) {
              return leaf_of_[x[1]] < leaf_of_[y[1]];
            });
      },
      256);
  return sorted;
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
    // The face pairs met, in order (met_face_pairs); the primitive boxes of their faces alone
    // (most faces meet none); then the candidates of fixed chunks of the face pairs, each chunk
    // into a list of its own, joined in order.
    const std::vector<std::array<std::uint32_t, 2>> met = met_face_pairs(mesh_pairs);
    parallel_for(
        met.size(),
        [&](std::size_t i) {
          want_primitives(met[i][0]);
          want_primitives(met[i][1]);
        },
        1024);
    sweep_primitives_of_met_faces();
    emit_in_chunks(
        met.size(), 512,
        [&](std::size_t i, const auto& push) {
          if (i + kPrefetchAhead < met.size()) prefetch_face(met[i + kPrefetchAhead][1]);
          const auto [a, b] = met[i];
          collision::emit_face_pair_candidates(faces[a], swept_[a], primitives_[a], a, owners_[a],
                                               faces[b], swept_[b], primitives_[b], b, owners_[b],
                                               push);
        },
        all, distances);
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
    // their ancestors (unions only).
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
    parallel_for(faces.size(), [&](std::size_t i) {
      const std::uint32_t face = faces[i];
      swept_[face] = collision::sweep_face(positions, motion, reach, faces_of[face]);
      primitives_state_[face] = kPrimitivesStale;
      boxes_[leaf_of_[face]] = swept_[face].box;
    });
    // Their ancestors' boxes, children first (a parent precedes its children in preorder): the
    // unions a refit of every parent would give, the other parents' being unchanged.
    std::vector<std::uint32_t> ancestors;
    {
      std::vector<std::uint8_t> listed(nodes.size(), 0u);
      for (const std::uint32_t face : faces) {
        for (std::uint32_t i = nodes[leaf_of_[face]].parent;
             i != gpu::kBvhInternal && listed[i] == 0u; i = nodes[i].parent) {
          listed[i] = 1u;
          ancestors.push_back(i);
        }
      }
    }
    std::sort(ancestors.begin(), ancestors.end(), std::greater<>());
    for (const std::uint32_t i : ancestors) {
      const gpu::Box& l = boxes_[nodes[i].left];
      const gpu::Box& r = boxes_[nodes[i].right];
      boxes_[i] = {glm::min(l.min, r.min), glm::max(l.max, r.max)};
    }
    // Each widened face's face pairs, with the pair's faces as find() orders them (the first
    // mesh's face first; within one mesh the lower face first), sorted: the order does not
    // depend on the trees (which the GL and CPU backends rebuild on schedules of their own) nor
    // on the threads that query them. A pair of two widened faces is met from both: each keeps
    // the candidates it is responsible for (below), so that every candidate comes once.
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
    std::vector<std::vector<FacePair>> met(faces.size());
    parallel_for(
        faces.size(),
        [&](std::size_t i) {
          const std::uint32_t face = faces[i];
          const std::uint32_t mesh = faces_of[face].body;
          for (const std::uint32_t p : mesh_pairs) {
            const gpu::BodyPair& mp = mesh_pairs_[p];
            if (mesh != mp.a && mesh != mp.b) continue;
            const bool first = mesh == mp.a;
            collision::query_bvh(
                nodes.data(), boxes_.data(), trees_.tree(first ? mp.b : mp.a).root,
                boxes_[leaf_of_[face]], [&](std::uint32_t other) {
                  if (mp.a == mp.b) {
                    if (other != face)
                      met[i].push_back({p, std::min(face, other), std::max(face, other), face});
                  } else {
                    met[i].push_back({p, first ? face : other, first ? other : face, face});
                  }
                });
          }
        },
        8);
    std::vector<FacePair> pairs;
    for (const std::vector<FacePair>& list : met)
      pairs.insert(pairs.end(), list.begin(), list.end());
    std::sort(pairs.begin(), pairs.end());
    for (const FacePair& fp : pairs) {
      want_primitives(fp.a);
      want_primitives(fp.b);
    }
    sweep_primitives_of_met_faces();
    const auto widened_vertex = [&](std::uint32_t mesh, std::uint32_t v) {
      return is_widened[vertex_first_[mesh] + v] != 0u;
    };
    // The candidates of fixed chunks of the sorted face pairs, joined in order.
    emit_in_chunks(
        pairs.size(), 256,
        [&](std::size_t i, const auto& push) {
          const FacePair& fp = pairs[i];
          // A candidate involves a widened vertex when its vertex (or an edge's end) is one, or
          // its face has one as a corner. The widened face that owns such a vertex or edge
          // emits it; a candidate whose widened part is only the face (or the second edge) is
          // emitted from that.
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
              swept_[fp.b], primitives_[fp.b], fp.b, owners_[fp.b], push, responsible);
        },
        out, &distances);
  });
  return out;
}

}  // namespace deformcd::cpu
