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
  explicit FclContestant(const WorldState& state) : state_(state) {
    for (int b = 0; b < 2; ++b) {
      const gpu::ObjectInfo& o = state.objects[b];
      std::vector<fcl::Triangle> triangles;
      for (std::uint32_t f = o.face_offset; f < o.face_offset + o.face_count; ++f) {
        const gpu::Face& face = state.faces[f];
        triangles.emplace_back(face.a - o.node_offset, face.b - o.node_offset,
                               face.c - o.node_offset);
      }
      auto model = std::make_shared<Model>();
      model->beginModel();
      model->addSubModel(points(state.positions, b), triangles);
      model->endModel();
      models_[b] = model;
      objects_[b] = std::make_unique<fcl::CollisionObjectd>(model);
    }
  }

  std::size_t detect(const std::vector<glm::vec4>& positions) override {
    for (int b = 0; b < 2; ++b) {
      models_[b]->beginUpdateModel();
      models_[b]->updateSubModel(points(positions, b));
      models_[b]->endUpdateModel(true, true);  // refit, bottom-up
      objects_[b]->computeAABB();
    }
    fcl::CollisionRequestd request(100000000, true);  // every contact, with contact points
    fcl::CollisionResultd result;
    fcl::collide(objects_[0].get(), objects_[1].get(), request, result);
    return result.numContacts();
  }

 private:
  std::vector<fcl::Vector3d> points(const std::vector<glm::vec4>& positions, int body) const {
    const gpu::ObjectInfo& o = state_.objects[body];
    std::vector<fcl::Vector3d> out;
    out.reserve(o.node_count);
    for (std::uint32_t i = o.node_offset; i < o.node_offset + o.node_count; ++i) {
      out.emplace_back(positions[i].x, positions[i].y, positions[i].z);
    }
    return out;
  }

  const WorldState& state_;
  std::shared_ptr<Model> models_[2];
  std::unique_ptr<fcl::CollisionObjectd> objects_[2];
};

}  // namespace

std::unique_ptr<PeerContestant> make_fcl_contestant(const WorldState& state) {
  return std::make_unique<FclContestant>(state);
}

}  // namespace deformcd::bench
