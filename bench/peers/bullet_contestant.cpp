// Bullet 3.24's dynamic AABB tree, btDbvt, as btSoftBody keeps one over its faces (m_fdbvt),
// then CGAL's exact triangle test on each candidate: what a soft-body user of Bullet has in hand
// to find the intersecting triangle pairs of two deforming meshes.
//  - One btDbvt per mesh, a leaf per triangle (its index in the leaf's data), built once on the
//    rest positions and balanced with optimizeTopDown() (untimed).
//  - Each frame, as btSoftBody does for its face tree (the deformable solver's
//    btDeformableBodySolver::predictDeformableMotion): every leaf given its triangle's new box,
//    m_fdbvt.update(leaf, volume) (the leaf taken out and reinserted from the root), then
//    optimizeIncremental(1). The boxes are the triangles' own, without btSoftBody's collision
//    margin or velocity sweep: an exact discrete test needs neither, and they only add
//    candidates.
//  - collideTT between the two face trees' roots. (btSoftBody's own soft-soft collision runs
//    collideTT between one body's node tree and the other's face tree, both ways, for
//    vertex-face contacts with a margin; triangle pairs need the two face trees.)
//  - Bullet has no exact triangle-triangle test (btSoftBody's face-face contacts are distances
//    with a margin; GIMPACT's triangle clipping is float with a margin): each candidate goes to
//    the same exact test as the CGAL row's, CGAL's do_intersect on Epick triangles.
// Debian's Bullet is built in float (btScalar = float), the precision of the positions.

#include <BulletCollision/BroadphaseCollision/btDbvt.h>

#include <cstdint>
#include <memory>

#include "exact_triangle_test.h"
#include "peer_contestants.h"

namespace deformcd::bench {

namespace {

btDbvtVolume triangle_volume(const std::vector<glm::vec3>& p, const Triangle& t) {
  btVector3 corners[3];
  for (int i = 0; i < 3; ++i)
    corners[i] = btVector3(p[t[i]].x, p[t[i]].y, p[t[i]].z);
  return btDbvtVolume::FromPoints(corners, 3);
}

std::uint32_t face_of(const btDbvtNode* leaf) {
  return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(leaf->data));
}

// Called by collideTT for every pair of leaves whose boxes overlap (a from mesh 0).
struct ExactCollider final : btDbvt::ICollide {
  ExactCollider(const std::vector<CollisionMesh>& meshes, const FramePositions& positions,
                std::vector<FacePair>* pairs)
      : meshes_(meshes), positions_(positions), pairs_(pairs) {}

  void Process(const btDbvtNode* a, const btDbvtNode* b) override {
    const std::uint32_t fa = face_of(a);
    const std::uint32_t fb = face_of(b);
    ++tested;
    if (!exact_triangles_intersect(positions_[0], meshes_[0].triangles[fa], positions_[1],
                                   meshes_[1].triangles[fb]))
      return;
    ++found;
    if (pairs_ != nullptr) pairs_->emplace_back(fa, fb);
  }

  std::size_t found = 0;
  std::size_t tested = 0;

 private:
  const std::vector<CollisionMesh>& meshes_;
  const FramePositions& positions_;
  std::vector<FacePair>* pairs_;
};

class BulletContestant final : public PeerContestant {
 public:
  BulletContestant(const std::vector<CollisionMesh>& meshes, const FramePositions& rest)
      : meshes_{meshes[0], meshes[1]} {
    for (int m = 0; m < 2; ++m) {
      const std::vector<Triangle>& triangles = meshes_[m].triangles;
      leaves_[m].reserve(triangles.size());
      for (std::size_t f = 0; f < triangles.size(); ++f) {
        leaves_[m].push_back(
            trees_[m].insert(triangle_volume(rest[m], triangles[f]), reinterpret_cast<void*>(f)));
      }
      trees_[m].optimizeTopDown();
    }
  }

  std::size_t detect(const FramePositions& positions, std::vector<FacePair>* pairs) override {
    for (int m = 0; m < 2; ++m) {
      const std::vector<Triangle>& triangles = meshes_[m].triangles;
      for (std::size_t f = 0; f < triangles.size(); ++f) {
        btDbvtVolume volume = triangle_volume(positions[m], triangles[f]);
        trees_[m].update(leaves_[m][f], volume);
      }
      trees_[m].optimizeIncremental(1);
    }
    ExactCollider collider(meshes_, positions, pairs);
    trees_[0].collideTT(trees_[0].m_root, trees_[1].m_root, collider);
    candidates_ = collider.tested;
    return collider.found;
  }

  [[nodiscard]] std::size_t candidates() const override { return candidates_; }

 private:
  std::vector<CollisionMesh> meshes_;
  btDbvt trees_[2];
  std::vector<btDbvtNode*> leaves_[2];
  std::size_t candidates_ = 0;
};

}  // namespace

std::unique_ptr<PeerContestant> make_bullet_contestant(const std::vector<CollisionMesh>& meshes,
                                                       const FramePositions& rest) {
  return std::make_unique<BulletContestant>(meshes, rest);
}

}  // namespace deformcd::bench
