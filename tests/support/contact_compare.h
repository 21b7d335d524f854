#pragma once
// Comparing contact lists in tests: equal field by field, segments bit for bit.

#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "deformcd/collision.h"

namespace deformcd::test {

inline auto contact_key(const Contact& c) {
  return std::tie(c.a.body, c.a.face, c.a.nodes, c.b.body, c.b.face, c.b.nodes, c.coplanar,
                  c.segment[0].x, c.segment[0].y, c.segment[0].z, c.segment[1].x, c.segment[1].y,
                  c.segment[1].z);
}

/// Empty when equal; otherwise what differs first.
inline std::string contacts_difference(const std::vector<Contact>& x,
                                       const std::vector<Contact>& y) {
  std::ostringstream out;
  if (x.size() != y.size()) out << x.size() << " vs " << y.size() << " contacts; ";
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
    if (contact_key(x[i]) != contact_key(y[i])) {
      out << "contact " << i << " differs: (" << x[i].a.body << "," << x[i].a.face << ")-("
          << x[i].b.body << "," << x[i].b.face << ") vs (" << y[i].a.body << "," << y[i].a.face
          << ")-(" << y[i].b.body << "," << y[i].b.face << ")";
      break;
    }
  }
  return out.str();
}

}  // namespace deformcd::test
