#include "peer_contestants.h"

#include <cstddef>

#include "deformcd/error.h"

namespace deformcd::bench {

#ifdef DEFORMCD_HAS_FCL
std::unique_ptr<PeerContestant> make_fcl_contestant(const std::vector<CollisionMesh>& meshes,
                                                    const FramePositions& rest,
                                                    const FclOptions& options);
#endif
#ifdef DEFORMCD_HAS_CGAL
std::unique_ptr<PeerContestant> make_cgal_contestant(const std::vector<CollisionMesh>& meshes,
                                                     std::ptrdiff_t cutoff, bool parallel);
#endif
#ifdef DEFORMCD_HAS_BULLET
std::unique_ptr<PeerContestant> make_bullet_contestant(const std::vector<CollisionMesh>& meshes,
                                                       const FramePositions& rest);
#endif

std::vector<PeerInfo> peers() {
  std::vector<PeerInfo> list;
#ifdef DEFORMCD_HAS_FCL
  list.push_back({"fcl-aabb-update-contacts", 1,
                  "FCL BVHModel<AABBd> updated (swept leaves), collide() with contact points"});
  list.push_back({"fcl-aabb-contacts", 1,
                  "FCL BVHModel<AABBd> refit, collide() with enable_contact (contact points too)"});
  list.push_back({"fcl-aabb", 1, "FCL BVHModel<AABBd> refit, collide(), pairs only"});
  list.push_back({"fcl-obbrss", 1, "FCL BVHModel<OBBRSSd> refit, collide(), pairs only"});
#endif
#ifdef DEFORMCD_HAS_CGAL
  list.push_back({"cgal-cutoff10", 1, "CGAL box_intersection_d, cutoff 10 + do_intersect"});
  list.push_back({"cgal", 1, "CGAL box_intersection_d, cutoff 2000 + do_intersect"});
  list.push_back(
      {"cgal-parallel", 0, "CGAL box_intersection_d<Parallel_tag>, cutoff 2000 + do_intersect"});
#endif
#ifdef DEFORMCD_HAS_BULLET
  list.push_back({"bullet-dbvt", 1, "Bullet btDbvt per mesh, update + collideTT, + do_intersect"});
#endif
  return list;
}

std::unique_ptr<PeerContestant> make_peer(const std::string& name,
                                          const std::vector<CollisionMesh>& meshes,
                                          const FramePositions& rest) {
  if (meshes.size() < 2 || rest.size() < 2) throw Error("a peer comparison needs two meshes");
#ifdef DEFORMCD_HAS_FCL
  if (name == "fcl-aabb-update-contacts")
    return make_fcl_contestant(meshes, rest, {.contacts = true, .swept = true});
  if (name == "fcl-aabb-contacts") return make_fcl_contestant(meshes, rest, {.contacts = true});
  if (name == "fcl-aabb") return make_fcl_contestant(meshes, rest, {});
  if (name == "fcl-obbrss") return make_fcl_contestant(meshes, rest, {.obbrss = true});
#endif
#ifdef DEFORMCD_HAS_CGAL
  if (name == "cgal-cutoff10") return make_cgal_contestant(meshes, 10, false);
  if (name == "cgal") return make_cgal_contestant(meshes, 2000, false);
  if (name == "cgal-parallel") return make_cgal_contestant(meshes, 2000, true);
#endif
#ifdef DEFORMCD_HAS_BULLET
  if (name == "bullet-dbvt") return make_bullet_contestant(meshes, rest);
#endif
  throw Error("peer '" + name + "' is not in this build");
}

}  // namespace deformcd::bench
