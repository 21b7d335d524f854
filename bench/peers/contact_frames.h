#pragma once
// The frames a peer comparison runs on: a shipped scene replayed on the CPU backend, keeping the
// node positions of the frames where the bodies are in contact. Every contestant then detects
// the collisions of exactly these positions.

#include <string>
#include <vector>

#include "deformcd/world_state.h"

namespace deformcd::bench {

struct ContactFrames {
  WorldState state;                               ///< the scene's world (rest lists, faces)
  std::vector<std::vector<glm::vec4>> positions;  ///< per contact frame, all nodes
  std::vector<std::size_t> contacts;              ///< per contact frame (face pairs)
};

/// Steps scene `name` (scenes/NAME.json) through `frames` frames on the CPU and keeps the frames
/// with contacts, at most `keep` of them evenly spread.
[[nodiscard]] ContactFrames contact_frames(const std::string& name, int frames, int keep);

}  // namespace deformcd::bench
