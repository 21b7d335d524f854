#pragma once
// Pair for pair, a contestant's contacts against deformcd's on the same frames. Counts alone
// could hide a contestant that misses some pairs and finds as many others: the sorted
// (triangle of mesh 0, triangle of mesh 1) lists are compared, and every pair in one list only
// is put to an exact oracle (CGAL's do_intersect with exact predicates on the same float
// positions) to say who is off and whether deformcd's float test may be (its uncertain zone).

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "contact_frames.h"

namespace deformcd::bench {

/// A contact between triangle `first` of mesh 0 and triangle `second` of mesh 1.
using FacePair = std::pair<std::uint32_t, std::uint32_t>;

/// Per contact frame, its pairs sorted.
using FramePairs = std::vector<std::vector<FacePair>>;

struct PairCheck {
  std::size_t reference = 0;  ///< deformcd's pairs over the frames
  std::size_t found = 0;      ///< the contestant's
  std::size_t differ = 0;     ///< pairs in one list only
  /// Of those, pairs where deformcd's float answer is not the exact one but the pair lies in
  /// the float test's uncertain zone (the contestant has the exact answer).
  std::size_t zone = 0;
  /// Pairs where deformcd has the exact answer and the contestant has not.
  std::size_t contestant_off = 0;
  /// Pairs where deformcd is off the exact answer outside its uncertain zone (a bug), or that
  /// no oracle could classify (a build without CGAL).
  std::size_t unexplained = 0;
  std::string first_unexplained;  ///< the first of those, for the error message

  /// False when the contestant and deformcd did not do the same work: an unexplained pair, or
  /// more pairs in one list only than 0.5 % of deformcd's (at least 2).
  [[nodiscard]] bool acceptable() const;
};

/// Compares `contestant` with `reference` (deformcd's), frame by frame, both sorted.
[[nodiscard]] PairCheck check_pairs(const ContactFrames& frames, const FramePairs& reference,
                                    const FramePairs& contestant);

/// The exact answer for triangles p and q, and whether a float answer other than it lies in
/// the uncertain zone of deformcd's test. `known` is false when this build has no oracle.
struct ExactVerdict {
  bool known = false;
  bool intersect = false;
  bool in_zone = false;  ///< meaningful when deformcd's answer is not `intersect`
};

/// `deformcd_found`: whether deformcd reported the pair.
[[nodiscard]] ExactVerdict exact_verdict(const glm::vec3 p[3], const glm::vec3 q[3],
                                         bool deformcd_found);

}  // namespace deformcd::bench
