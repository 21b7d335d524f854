#include "core/sim/simulation_backend.h"

#include "deformcd/error.h"

namespace deformcd::sim {

void check_node_range(std::uint32_t first, std::size_t count, std::size_t node_count) {
  if (first > node_count || count > node_count - first) {
    throw Error("nodes " + std::to_string(first) + " to " + std::to_string(first + count) +
                " are outside the simulation's " + std::to_string(node_count) + " nodes");
  }
}

}  // namespace deformcd::sim
