// The checks GlSimulation::upload runs before allocating (no GL needed): buffer sizes against
// a limit and the consistency of a SimulationState's arrays.

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/sim/node_force_lists.h"
#include "deformcd/body.h"
#include "deformcd/error.h"
#include "deformcd/simulation_state.h"
#include "gl/sim_test_worlds.h"
#include "gpu/gl/simulation_upload_checks.h"

namespace deformcd::gl {
namespace {

SimulationState two_cube_world() {
  BodyInit a, b;
  a.body = build_body(test::tet_grid(1, 1, 1, 1.0));
  b.body = build_body(test::tet_grid(2, 1, 1, 1.0, {3.0, 0.0, 0.0}));
  return assemble_simulation({a, b});
}

TEST(SimulationBufferSizes, ListsEveryBufferWithItsBindingAndSize) {
  const SimulationState w = two_cube_world();
  const sim::SpringEdges edges = sim::build_spring_edges(w);
  const sim::TetCorners corners = sim::build_tet_corners(w);
  // The step's own layout: each spring edge once (springs share edges between tetrahedra).
  ASSERT_LT(edges.size(), w.springs.size());
  const std::vector<BufferSize> sizes = simulation_buffer_sizes(w, edges, corners);
  ASSERT_EQ(sizes.size(), 13u);
  const std::vector<std::uint32_t> bindings = {0, 1, 2, 3, 12, 13, 14, 15, 16, 17, 18, 19, 20};
  const std::vector<std::uint64_t> bytes = {16 * w.node_count(),
                                            16 * w.node_count(),
                                            16 * edges.size(),
                                            16 * w.node_count(),
                                            32 * 2,
                                            4 * w.node_count(),
                                            16 * edges.size(),
                                            4 * (w.node_count() + 1),
                                            8 * w.node_spring_list.size(),
                                            32 * corners.tets.size(),
                                            16 * std::uint64_t{corners.slot_count},
                                            4 * (w.node_count() + 1),
                                            16 * corners.tets.size()};
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    EXPECT_EQ(sizes[i].binding, bindings[i]) << sizes[i].name;
    EXPECT_EQ(sizes[i].bytes(), bytes[i]) << sizes[i].name;
  }
  EXPECT_EQ(sizes[2].name, "Spring Edge");
}

TEST(CheckBufferSizes, AcceptsABufferExactlyAtTheLimit) {
  const std::vector<BufferSize> sizes = {{"Spring Edge", 2, 4, 16}};
  EXPECT_NO_THROW(check_buffer_sizes(sizes, 64, "the limit"));
}

TEST(CheckBufferSizes, NamesEveryBufferOverTheLimitWithItsSizeAndTheLimit) {
  const std::vector<BufferSize> sizes = {
      {"Node Position", 0, 4, 16}, {"Spring Edge", 2, 5, 16}, {"Edge State", 14, 6, 16}};
  try {
    check_buffer_sizes(sizes, 64, "the device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE");
    FAIL() << "expected GlError";
  } catch (const GlError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("the device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE (64 bytes)"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("Spring Edge (SSBO 2): 80 bytes (5 x 16)"), std::string::npos) << what;
    EXPECT_NE(what.find("Edge State (SSBO 14): 96 bytes (6 x 16)"), std::string::npos) << what;
    EXPECT_EQ(what.find("Node Position"), std::string::npos) << what;
  }
}

TEST(CheckWorldConsistency, AcceptsAnAssembledWorld) {
  EXPECT_NO_THROW(check_world_consistency(two_cube_world()));
  EXPECT_NO_THROW(check_world_consistency(assemble_simulation({})));
}

struct Corruption {
  std::string what;                             // for the failure message
  std::function<void(SimulationState&)> apply;  // breaks one thing
  std::string expected;                         // part of the error message
};

TEST(CheckWorldConsistency, NamesWhatDoesNotFit) {
  const std::vector<Corruption> corruptions = {
      {"short velocities", [](SimulationState& w) { w.velocities.pop_back(); }, "velocities has"},
      {"short node_body", [](SimulationState& w) { w.node_body.pop_back(); }, "node_body has"},
      {"short spring forces", [](SimulationState& w) { w.spring_forces.pop_back(); },
       "spring_forces has"},
      {"short offsets", [](SimulationState& w) { w.node_spring_offset.pop_back(); },
       "node_spring_offset has"},
      {"spring node", [](SimulationState& w) { w.springs[5].a = 1000; },
       "spring 5 joins nodes 1000"},
      {"node body", [](SimulationState& w) { w.node_body[3] = 9; }, "node 3 belongs to body 9"},
      {"first offset", [](SimulationState& w) { w.node_spring_offset[0] = 1; },
       "node_spring_offset[0] is not 0"},
      {"decreasing offsets", [](SimulationState& w) { w.node_spring_offset[2] = 0; },
       "decreases at node 1"},
      {"list length", [](SimulationState& w) { w.node_spring_list.pop_back(); },
       "node_spring_list has"},
      {"zero tag", [](SimulationState& w) { w.node_spring_list[4] = 0; },
       "node_spring_list[4] = 0"},
      {"tag past the springs",
       [](SimulationState& w) { w.node_spring_list[6] = -static_cast<int>(w.springs.size()) - 1; },
       "node_spring_list[6] = -"},
      {"most negative tag",
       [](SimulationState& w) { w.node_spring_list[1] = std::numeric_limits<std::int32_t>::min(); },
       "node_spring_list[1] = -2147483648"},
  };
  for (const Corruption& c : corruptions) {
    SimulationState w = two_cube_world();
    c.apply(w);
    try {
      check_world_consistency(w);
      ADD_FAILURE() << c.what << ": expected Error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(c.expected), std::string::npos)
          << c.what << ": " << e.what();
    }
  }
}

}  // namespace
}  // namespace deformcd::gl
