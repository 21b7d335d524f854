#pragma once
// The peer libraries of the comparison, behind one small interface: given each mesh's vertex
// positions of a frame, find the intersecting triangle pairs between mesh 0 and mesh 1.

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "contact_frames.h"

namespace deformcd::bench {

class PeerContestant {
 public:
  virtual ~PeerContestant() = default;
  /// Intersecting triangle pairs between mesh 0 and mesh 1 at these positions.
  virtual std::size_t detect(const FramePositions& positions) = 0;
};

/// The peers this build has ("fcl", "cgal"), each only when found at configure time.
[[nodiscard]] std::vector<std::string> peer_names();

/// The peer `name` set up for the two meshes, its structures built on `rest`.
[[nodiscard]] std::unique_ptr<PeerContestant> make_peer(const std::string& name,
                                                        const std::vector<CollisionMesh>& meshes,
                                                        const FramePositions& rest);

}  // namespace deformcd::bench
