#pragma once
// The frames a peer comparison runs on: a shipped scene replayed on the CPU backend, keeping the
// positions of the frames where the first two bodies are in contact. Every contestant then
// detects the collisions of exactly these positions, given as a caller would hold them: one xyz
// array per mesh.

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "deformcd/detector.h"

namespace deformcd::bench {

/// One frame: each mesh's vertex positions.
using FramePositions = std::vector<std::vector<glm::vec3>>;

struct ContactFrames {
  std::vector<CollisionMesh> meshes;      ///< the first two bodies' surfaces
  std::vector<FramePositions> positions;  ///< per contact frame
  std::vector<std::size_t> contacts;      ///< per contact frame (intersecting triangle pairs)

  [[nodiscard]] std::size_t face_count() const {
    return meshes[0].triangles.size() + meshes[1].triangles.size();
  }
};

/// Steps scene `name` (scenes/NAME.json) through `frames` frames on the CPU and keeps the frames
/// with contacts between its first two bodies, at most `keep` of them evenly spread.
[[nodiscard]] ContactFrames contact_frames(const std::string& name, int frames, int keep);

}  // namespace deformcd::bench
