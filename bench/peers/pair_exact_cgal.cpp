// The exact oracle of the pair check: CGAL's do_intersect with exact predicates on the float
// positions (converted to double exactly), and the uncertain-zone measures of the narrow
// phase's oracle tests (tests/support/triangle_separation.h), so that the benchmark and the
// tests allow deformcd the same disagreements.

#include <array>

#include "pair_check.h"
#include "support/triangle_separation.h"

namespace deformcd::bench {

ExactVerdict exact_verdict(const glm::vec3 p[3], const glm::vec3 q[3], bool deformcd_found) {
  const test::Tri tp = {p[0], p[1], p[2]};
  const test::Tri tq = {q[0], q[1], q[2]};
  ExactVerdict verdict;
  verdict.known = true;
  verdict.intersect = CGAL::do_intersect(test::to_cgal(tp), test::to_cgal(tq));
  if (verdict.intersect != deformcd_found)
    verdict.in_zone = test::disagreement_measure(tp, tq, verdict.intersect) < test::kZone;
  return verdict;
}

}  // namespace deformcd::bench
