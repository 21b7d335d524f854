#pragma once
// The peer libraries of the comparison, behind one small interface: given every node position
// of a frame, find the intersecting surface-triangle pairs between body 0 and body 1.

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "deformcd/world_state.h"

namespace deformcd::bench {

class PeerContestant {
 public:
  virtual ~PeerContestant() = default;
  /// Intersecting face pairs between the first two bodies at these node positions.
  virtual std::size_t detect(const std::vector<glm::vec4>& positions) = 0;
};

/// The peers this build has ("fcl", "cgal"), each only when found at configure time.
[[nodiscard]] std::vector<std::string> peer_names();

/// The peer `name` set up for `state`'s first two bodies (topology, rest positions).
[[nodiscard]] std::unique_ptr<PeerContestant> make_peer(const std::string& name,
                                                        const WorldState& state);

}  // namespace deformcd::bench
