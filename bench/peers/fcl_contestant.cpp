// FCL 0.7: one BVHModel<AABB> per body (the usual choice for deformable meshes: AABB trees
// refit cheaply), refitted from the frame's positions, then collide() with exhaustive contacts.

#include <fcl/fcl.h>

#include <memory>

#include "peer_contestants.h"

namespace deformcd::bench {

namespace {

using Model = fcl::BVHModel<fcl::AABBd>;

class FclContestant final : public PeerContestant {
 public:
  FclContestant(const std::vector<CollisionMesh>& meshes, const FramePositions& rest) {
    for (int m = 0; m < 2; ++m) {
      std::vector<fcl::Triangle> triangles;
      for (const Triangle& t : meshes[m].triangles)
        triangles.emplace_back(t[0], t[1], t[2]);
      auto model = std::make_shared<Model>();
      model->beginModel();
      model->addSubModel(points(rest[m]), triangles);
      model->endModel();
      models_[m] = model;
      objects_[m] = std::make_unique<fcl::CollisionObjectd>(model);
    }
  }

  std::size_t detect(const FramePositions& positions) override {
    for (int m = 0; m < 2; ++m) {
      models_[m]->beginUpdateModel();
      models_[m]->updateSubModel(points(positions[m]));
      models_[m]->endUpdateModel(true, true);  // refit, bottom-up
      objects_[m]->computeAABB();
    }
    fcl::CollisionRequestd request(100000000, true);  // every contact, with contact points
    fcl::CollisionResultd result;
    fcl::collide(objects_[0].get(), objects_[1].get(), request, result);
    return result.numContacts();
  }

 private:
  static std::vector<fcl::Vector3d> points(const std::vector<glm::vec3>& positions) {
    std::vector<fcl::Vector3d> out;
    out.reserve(positions.size());
    for (const glm::vec3& p : positions)
      out.emplace_back(p.x, p.y, p.z);
    return out;
  }

  std::shared_ptr<Model> models_[2];
  std::unique_ptr<fcl::CollisionObjectd> objects_[2];
};

}  // namespace

std::unique_ptr<PeerContestant> make_fcl_contestant(const std::vector<CollisionMesh>& meshes,
                                                    const FramePositions& rest) {
  return std::make_unique<FclContestant>(meshes, rest);
}

}  // namespace deformcd::bench
