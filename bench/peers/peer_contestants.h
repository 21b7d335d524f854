#pragma once
// The peer libraries of the comparison, behind one small interface: given each mesh's vertex
// positions of a frame, find the intersecting triangle pairs between mesh 0 and mesh 1.

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "contact_frames.h"
#include "pair_check.h"

namespace deformcd::bench {

class PeerContestant {
 public:
  virtual ~PeerContestant() = default;
  /// Intersecting triangle pairs between mesh 0 and mesh 1 at these positions. When `pairs` is
  /// not null, each pair found is also appended to it, in any order (the timed runs pass null).
  virtual std::size_t detect(const FramePositions& positions, std::vector<FacePair>* pairs) = 0;
  /// The triangle pairs the last detect() gave its triangle test; 0 when the library hides it.
  [[nodiscard]] virtual std::size_t candidates() const { return 0; }
};

/// A peer of this build: its name in the benchmark's rows, the threads it runs on (0: every
/// core) and what it runs, for the output.
struct PeerInfo {
  std::string name;
  int threads = 1;
  std::string configuration;
};

/// FCL's configurations (fcl_contestant.cpp).
struct FclOptions {
  bool obbrss = false;    ///< BVHModel<OBBRSSd>, else BVHModel<AABBd>
  bool contacts = false;  ///< collide() with enable_contact (contact points too), else pairs only
  bool swept = false;     ///< beginUpdateModel (swept leaves), else beginReplaceModel
};

/// The peers this build has, each only when its library was found at configure time.
[[nodiscard]] std::vector<PeerInfo> peers();

/// The peer `name` set up for the two meshes, its structures built on `rest`.
[[nodiscard]] std::unique_ptr<PeerContestant> make_peer(const std::string& name,
                                                        const std::vector<CollisionMesh>& meshes,
                                                        const FramePositions& rest);

}  // namespace deformcd::bench
