// FCL 0.7: one BVHModel per body, its leaves refitted from the frame's positions each frame,
// then collide() for every intersecting triangle pair.
//  - Refit: beginReplaceModel / replaceSubModel / endReplaceModel(refit, bottom-up): the
//    model's tree kept, each leaf's volume fitted to its triangle and each node's to its two
//    children. beginUpdateModel / updateSubModel / endUpdateModel, which the first version of
//    this benchmark used (the row fcl-aabb-update-contacts), keeps the previous frame as
//    prev_vertices and fits every leaf around the triangle's old and new positions, a swept
//    volume for continuous collision: looser boxes for the same pairs (4.5-5.2x slower on the
//    phase scenes, docs/benchmarks.md).
//  - BV: AABB (cheap to refit, and a parent merged from its children is exact; the fastest of
//    FCL's volumes on a deforming scene as an FCL user measured them, fcl issue #425: AABB refit
//    13 ms, OBBRSS refit 262 ms) or OBBRSS (what FCL's examples use for rigid meshes; merging
//    two children's OBBs on refit is costly and loose).
//  - Contacts: with enable_contact, FCL also computes each pair's contact points, normal and
//    penetration, which deformcd's pair list does not give; without it, only the triangle ids
//    (the same intersection test, Intersect::intersect_Triangle in double).

#include <fcl/fcl.h>

#include <memory>

#include "peer_contestants.h"

namespace deformcd::bench {

namespace {

template <typename BV>
class FclContestant final : public PeerContestant {
 public:
  FclContestant(const std::vector<CollisionMesh>& meshes, const FramePositions& rest, bool contacts,
                bool swept)
      : contacts_(contacts), swept_(swept) {
    for (int m = 0; m < 2; ++m) {
      std::vector<fcl::Triangle> triangles;
      for (const Triangle& t : meshes[m].triangles)
        triangles.emplace_back(t[0], t[1], t[2]);
      to_points(rest[m], points_[m]);
      auto model = std::make_shared<fcl::BVHModel<BV>>();
      model->beginModel();
      model->addSubModel(points_[m], triangles);
      model->endModel();
      models_[m] = model;
      objects_[m] = std::make_unique<fcl::CollisionObjectd>(model);
    }
  }

  std::size_t detect(const FramePositions& positions, std::vector<FacePair>* pairs) override {
    for (int m = 0; m < 2; ++m) {
      to_points(positions[m], points_[m]);
      if (swept_) {
        models_[m]->beginUpdateModel();
        models_[m]->updateSubModel(points_[m]);
        models_[m]->endUpdateModel(true, true);  // refit, bottom-up
      } else {
        models_[m]->beginReplaceModel();
        models_[m]->replaceSubModel(points_[m]);
        models_[m]->endReplaceModel(true, true);  // refit, bottom-up
      }
      objects_[m]->computeAABB();
    }
    fcl::CollisionRequestd request(100000000, contacts_);  // every pair
    fcl::CollisionResultd result;
    fcl::collide(objects_[0].get(), objects_[1].get(), request, result);
    if (pairs != nullptr) {
      for (std::size_t i = 0; i < result.numContacts(); ++i) {
        const fcl::Contactd& c = result.getContact(i);
        pairs->emplace_back(static_cast<std::uint32_t>(c.b1), static_cast<std::uint32_t>(c.b2));
      }
    }
    return result.numContacts();
  }

 private:
  // FCL's models are in double: the frame's float positions converted, into a kept buffer.
  static void to_points(const std::vector<glm::vec3>& positions, std::vector<fcl::Vector3d>& out) {
    out.resize(positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i)
      out[i] = fcl::Vector3d(positions[i].x, positions[i].y, positions[i].z);
  }

  bool contacts_;
  bool swept_;
  std::vector<fcl::Vector3d> points_[2];
  std::shared_ptr<fcl::BVHModel<BV>> models_[2];
  std::unique_ptr<fcl::CollisionObjectd> objects_[2];
};

}  // namespace

std::unique_ptr<PeerContestant> make_fcl_contestant(const std::vector<CollisionMesh>& meshes,
                                                    const FramePositions& rest,
                                                    const FclOptions& options) {
  if (options.obbrss) {
    return std::make_unique<FclContestant<fcl::OBBRSSd>>(meshes, rest, options.contacts,
                                                         options.swept);
  }
  return std::make_unique<FclContestant<fcl::AABBd>>(meshes, rest, options.contacts, options.swept);
}

}  // namespace deformcd::bench
