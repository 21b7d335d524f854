#include "pair_check.h"

#include <algorithm>
#include <iterator>
#include <sstream>

namespace deformcd::bench {

bool PairCheck::acceptable() const {
  const std::size_t limit = std::max<std::size_t>(2, reference / 200);
  return unexplained == 0 && differ <= limit;
}

PairCheck check_pairs(const ContactFrames& frames, const FramePairs& reference,
                      const FramePairs& contestant) {
  PairCheck check;
  for (std::size_t k = 0; k < reference.size(); ++k) {
    const std::vector<FacePair>& ours = reference[k];
    const std::vector<FacePair>& theirs = contestant[k];
    check.reference += ours.size();
    check.found += theirs.size();
    std::vector<FacePair> only_ours;
    std::vector<FacePair> only_theirs;
    std::set_difference(ours.begin(), ours.end(), theirs.begin(), theirs.end(),
                        std::back_inserter(only_ours));
    std::set_difference(theirs.begin(), theirs.end(), ours.begin(), ours.end(),
                        std::back_inserter(only_theirs));
    const FramePositions& positions = frames.positions[k];
    const auto classify = [&](const FacePair& pair, bool deformcd_found) {
      ++check.differ;
      glm::vec3 p[3];
      glm::vec3 q[3];
      for (int i = 0; i < 3; ++i) {
        p[i] = positions[0][frames.meshes[0].triangles[pair.first][i]];
        q[i] = positions[1][frames.meshes[1].triangles[pair.second][i]];
      }
      const ExactVerdict verdict = exact_verdict(p, q, deformcd_found);
      if (verdict.known && verdict.intersect != deformcd_found && verdict.in_zone) {
        ++check.zone;
      } else if (verdict.known && verdict.intersect == deformcd_found) {
        ++check.contestant_off;
      } else {
        if (check.unexplained++ == 0) {
          std::ostringstream text;
          text << "frame " << k << ", triangles (" << pair.first << ", " << pair.second
               << "): " << (deformcd_found ? "deformcd" : "the contestant") << " alone reports it, "
               << (verdict.known ? "the exact test says "
                                 : "no exact oracle in this build (CGAL not found)")
               << (verdict.known ? (verdict.intersect ? "intersecting" : "apart") : "")
               << (verdict.known ? ", outside the float test's uncertain zone" : "");
          check.first_unexplained = text.str();
        }
      }
    };
    for (const FacePair& pair : only_ours)
      classify(pair, true);
    for (const FacePair& pair : only_theirs)
      classify(pair, false);
  }
  return check;
}

}  // namespace deformcd::bench
