#pragma once
// What a run's contact response did, for the summaries of `run` and `render`: the frames that
// ended with contact constraints between bodies and those with a body's own, the most at once, the
// closest the surfaces came against the thickness they keep, the bodies asleep. On a response scene
// the intersection count alone reads as if nothing happened: 0 intersections is the response's
// success.

#include <cstdint>
#include <limits>
#include <string>

#include "deformcd/world.h"

namespace deformcd::app {

/// Gathered frame by frame from World::response_counts().
struct ResponseTally {
  int frames = 0;  ///< frames added
  /// Frames that ended with at least one constraint between two bodies.
  int frames_with_constraints = 0;
  int first_active = -1;  ///< the first and last of them
  int last_active = -1;
  std::uint64_t most_constraints = 0;  ///< the most between bodies a frame ended with
  int most_at = -1;                    ///< the frame with that many
  int frames_with_own = 0;  ///< frames that ended with a constraint of a body with itself
  /// The closest pair relative to its thickness over the frames (ResponseCounts).
  float closest_distance = std::numeric_limits<float>::infinity();
  float closest_thickness = 0.0f;
  int closest_at = -1;
  std::uint64_t asleep = 0;  ///< bodies asleep after the last frame added

  /// After frame `frame`'s step: the world's response counts.
  void add(int frame, const ResponseCounts& counts);
};

/// One line, without a label or a line break, e.g. "constraints between bodies in 57 of 200
/// frames (12-68), at most 1234 at once (frame 30); a body's own (self-contact) in 200 frames;
/// closest surfaces 0.0041 m apart, 0.82 x the thickness kept (0.0050 m)", then ", 1 of 2
/// bodies asleep at the end" when `sleeps`.
[[nodiscard]] std::string describe_response(const ResponseTally& tally, std::size_t bodies,
                                            bool sleeps);

}  // namespace deformcd::app
