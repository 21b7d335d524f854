// Issue 34, item 3: results must not depend on the units. A contact scene scaled by every power
// of ten inside the documented range (kMaxCoordinate, kMinMeshExtent) gives the same contact
// pairs; past it the detector refuses the positions with an InputError naming the mesh and the
// vertex, never a silently different answer (before: 4 "coplanar" contacts at 1e10 instead of
// 3, none at 3e-12 or 1.8e19).

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "deformcd/detector.h"
#include "deformcd/error.h"
#include "deformcd/limits.h"
#include "detector/detector_scenes.h"

namespace deformcd {
namespace {

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// Two spheres crossing each other and a draped cloth crossing both, all scaled by `scale`
// about the origin: general angles, shared edges, an open surface. Largest |coordinate| 1.6,
// smallest mesh extent 1.6 (before scaling).
std::vector<test::CallerMesh> scene(double scale) {
  std::vector<test::CallerMesh> meshes{test::sphere_mesh(2, 0.8f, {-0.3f, 0.0f, 0.0f}),
                                       test::sphere_mesh(2, 0.7f, {0.5f, 0.2f, 0.1f}),
                                       test::cloth_mesh(8, 1.6f, {0.1f, 0.1f, 0.0f}, 0.2f)};
  for (test::CallerMesh& m : meshes) {
    for (glm::vec3& p : m.positions)
      p = glm::vec3(glm::dvec3(p) * scale);
  }
  return meshes;
}

// The face pairs (mesh-major), or the InputError's message.
std::pair<Pairs, std::string> detect(double scale) {
  std::vector<test::CallerMesh> meshes = scene(scale);
  std::vector<CollisionMesh> collision;
  for (const test::CallerMesh& m : meshes)
    collision.push_back(m.mesh);
  Detector detector(std::move(collision), {.backend = BackendKind::kCpu, .threads = 1});
  for (std::size_t m = 0; m < meshes.size(); ++m)
    detector.set_positions(m, std::span<const glm::vec3>(meshes[m].positions));
  try {
    detector.detect();
  } catch (const InputError& e) {
    return {{}, e.what()};
  }
  Pairs pairs;
  for (const Contact& c : detector.contacts())
    pairs.emplace_back(c.a.body * 100000 + c.a.face, c.b.body * 100000 + c.b.face);
  return {pairs, ""};
}

TEST(CoordinateRange, EveryPowerOfTenInsideTheRangeGivesTheSamePairs) {
  const auto [reference, error] = detect(1.0);
  ASSERT_EQ(error, "");
  ASSERT_GT(reference.size(), 20u);
  // 1.6 * 1e8 <= kMaxCoordinate; 1.6 * 1e-10 >= kMinMeshExtent.
  for (int e = -10; e <= 8; ++e) {
    const auto [pairs, message] = detect(std::pow(10.0, e));
    EXPECT_EQ(message, "") << "1e" << e;
    EXPECT_EQ(pairs, reference) << "scaled by 1e" << e;
  }
}

TEST(CoordinateRange, PastTheRangeThePositionsAreRefusedNamingTheVertex) {
  for (int e : {9, 10, 19, 30}) {  // 1.6e9 and above
    const auto [pairs, message] = detect(std::pow(10.0, e));
    EXPECT_TRUE(pairs.empty()) << "1e" << e;
    EXPECT_NE(message.find("mesh 0 ('sphere'): vertex "), std::string::npos) << message;
    EXPECT_NE(message.find("outside +-1e9 (deformcd::kMaxCoordinate)"), std::string::npos)
        << message;
  }
  for (int e : {-11, -12, -20, -30}) {
    const auto [pairs, message] = detect(std::pow(10.0, e));
    EXPECT_TRUE(pairs.empty()) << "1e" << e;
    EXPECT_NE(message.find("mesh 0 ('sphere'): spans only"), std::string::npos) << message;
    EXPECT_NE(message.find("deformcd::kMinMeshExtent"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace deformcd
