#pragma once
// The `run --contacts` format: JSON Lines, one line per frame,
//   {"frame":k,"contacts":[{"a":{"body":0,"face":12,"nodes":[i,j,k]},"b":{...},
//                           "segment":[[x,y,z],[x,y,z]]}, ...]}
// contacts in World::contacts() order, so that the files of two runs compare line by line.
// Coordinates are the shortest decimal that reads back as the same float. Coplanar pairs have
// "coplanar":true and "segment":null.

#include <string>
#include <vector>

#include "deformcd/collision.h"

namespace deformcd::app {

/// One line, ending in '\n'.
[[nodiscard]] std::string contacts_json_line(int frame, const std::vector<Contact>& contacts);

/// The JSON array of the contacts, as in a line: [{"a":...,"b":...,"segment":...}, ...].
[[nodiscard]] std::string contacts_json_array(const std::vector<Contact>& contacts);

}  // namespace deformcd::app
