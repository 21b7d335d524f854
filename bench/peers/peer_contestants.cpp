#include "peer_contestants.h"

#include "deformcd/error.h"

namespace deformcd::bench {

#ifdef DEFORMCD_HAS_FCL
std::unique_ptr<PeerContestant> make_fcl_contestant(const std::vector<CollisionMesh>& meshes,
                                                    const FramePositions& rest);
#endif
#ifdef DEFORMCD_HAS_CGAL
std::unique_ptr<PeerContestant> make_cgal_contestant(const std::vector<CollisionMesh>& meshes);
#endif

std::vector<std::string> peer_names() {
  std::vector<std::string> names;
#ifdef DEFORMCD_HAS_FCL
  names.emplace_back("fcl");
#endif
#ifdef DEFORMCD_HAS_CGAL
  names.emplace_back("cgal");
#endif
  return names;
}

std::unique_ptr<PeerContestant> make_peer(const std::string& name,
                                          const std::vector<CollisionMesh>& meshes,
                                          const FramePositions& rest) {
  if (meshes.size() < 2 || rest.size() < 2) throw Error("a peer comparison needs two meshes");
#ifdef DEFORMCD_HAS_FCL
  if (name == "fcl") return make_fcl_contestant(meshes, rest);
#endif
#ifdef DEFORMCD_HAS_CGAL
  if (name == "cgal") return make_cgal_contestant(meshes);
#endif
  throw Error("peer '" + name + "' is not in this build");
}

}  // namespace deformcd::bench
