// The BoundingBox Face List built at pre-processing (the paper's Fig. 7).

#include "core/collision/leaf_boxes.h"

#include <set>

#include <gtest/gtest.h>

#include "deformcd/body.h"
#include "support/collision_fixtures.h"
#include "support/world_fixtures.h"

namespace deformcd::collision {
namespace {

TEST(LeafBoxes, LeafIndexNumbersTheCellsInOctreeOrder) {
  std::set<std::uint32_t> seen;
  for (std::uint32_t z = 0; z < 4; ++z)
    for (std::uint32_t y = 0; y < 4; ++y)
      for (std::uint32_t x = 0; x < 4; ++x) {
        const std::uint32_t i = leaf_index(x, y, z);
        EXPECT_LT(i, 64u);
        seen.insert(i);
        // The level-2 octant (which half along each axis) is the index's top three bits.
        EXPECT_EQ(i / 8u, (x / 2u) + 2u * (y / 2u) + 4u * (z / 2u));
      }
  EXPECT_EQ(seen.size(), 64u);
}

BodyInit grid_body(int n, double spacing, glm::dvec3 origin) {
  BodyInit init;
  init.body = build_body(test::tet_grid(n, n, n, spacing, origin));
  return init;
}

TEST(LeafBoxes, EveryFaceIsListedUnderTheCellsItsBoxOverlaps) {
  const test::CollisionFixture fixture =
      test::collision_fixture({grid_body(8, 0.125, glm::dvec3(0.0))});
  const CollisionData& w = fixture.data;
  ASSERT_EQ(w.mesh_count(), 1u);
  const gpu::MeshInfo& o = w.meshes[0];
  ASSERT_EQ(w.box_rows.size(), 64u);
  ASSERT_EQ(w.face_boxes.size(), w.faces.size());
  // Rows grouped box by box, in box order, and box_rows pointing at each group.
  std::uint32_t row = 0;
  for (std::uint32_t box = 0; box < 64; ++box) {
    EXPECT_EQ(w.box_rows[box].x, row);
    for (std::uint32_t r = row; r < row + w.box_rows[box].y; ++r)
      EXPECT_EQ(w.box_faces[r].box, box);
    row += w.box_rows[box].y;
  }
  EXPECT_EQ(row, o.box_face_count);
  EXPECT_EQ(w.box_faces.size(), o.box_face_count);
  // Each face's bit set is exactly the set of boxes listing it, and is not empty.
  std::vector<glm::uvec2> from_rows(w.faces.size(), glm::uvec2(0u));
  for (const gpu::BoxFace& r : w.box_faces)
    from_rows[r.face][r.box / 32u] |= 1u << (r.box % 32u);
  for (std::size_t f = 0; f < w.faces.size(); ++f) {
    EXPECT_EQ(from_rows[f], w.face_boxes[f]) << f;
    EXPECT_NE(w.face_boxes[f], glm::uvec2(0u)) << f;
  }
  // A 1 m cube cut in 8 along each axis: cell boundaries at 0.25 m fall on grid lines, so the
  // faces touching one (those whose box reaches 0.25, 0.5, 0.75) are listed twice along that
  // axis, and some faces more than once: N' > N.
  EXPECT_GT(o.box_face_count, o.face_count);
  // The interior cells (x, y, z all in 1..2) hold no surface face.
  for (std::uint32_t z = 1; z <= 2; ++z)
    for (std::uint32_t y = 1; y <= 2; ++y)
      for (std::uint32_t x = 1; x <= 2; ++x)
        EXPECT_EQ(w.box_rows[leaf_index(x, y, z)].y, 0u);
}

TEST(LeafBoxes, ListsOfSeveralBodiesFollowEachOther) {
  const test::CollisionFixture fixture = test::collision_fixture(
      {grid_body(2, 0.5, glm::dvec3(0.0)), grid_body(3, 0.2, glm::dvec3(5.0)),
       grid_body(1, 1.0, glm::dvec3(-5.0))});
  const CollisionData& w = fixture.data;
  ASSERT_EQ(w.meshes.size(), 3u);
  ASSERT_EQ(w.mesh_pairs.size(), 3u);
  EXPECT_EQ(w.mesh_pairs[0].a, 0u);
  EXPECT_EQ(w.mesh_pairs[0].b, 1u);
  EXPECT_EQ(w.mesh_pairs[2].a, 1u);
  EXPECT_EQ(w.mesh_pairs[2].b, 2u);
  ASSERT_EQ(w.box_rows.size(), 3u * 64u);
  std::uint32_t rows = 0;
  for (std::uint32_t b = 0; b < 3; ++b) {
    const gpu::MeshInfo& o = w.meshes[b];
    // Mesh b's 64 boxes are boxes 64 b to 64 b + 63 (the leaf-box arrays hold 64 per mesh).
    const std::uint32_t box_offset = 64u * b;
    EXPECT_EQ(o.box_face_offset, rows);
    for (std::uint32_t r = o.box_face_offset; r < o.box_face_offset + o.box_face_count; ++r) {
      EXPECT_GE(w.box_faces[r].face, o.face_offset);
      EXPECT_LT(w.box_faces[r].face, o.face_offset + o.face_count);
    }
    EXPECT_EQ(w.box_rows[box_offset].x, o.box_face_offset);
    rows += o.box_face_count;
  }
  EXPECT_EQ(rows, w.box_faces.size());
}

TEST(LeafBoxes, AFlatBodyUsesOneLayerOfCells) {
  // Two triangles in z = 0: no extent along z, all cells at z = 0, no division by zero.
  const std::vector<glm::vec4> p = {glm::vec4(0, 0, 0, 1), glm::vec4(1, 0, 0, 1),
                                    glm::vec4(0, 1, 0, 1), glm::vec4(1, 1, 0, 1)};
  const MeshVertices mesh{&p[0].x, 4u};
  const gpu::Face faces[2] = {{0, 1, 2, 0}, {1, 3, 2, 0}};
  const LeafBoxLists lists = build_leaf_box_lists(&mesh, faces, 2, 0);
  ASSERT_FALSE(lists.rows.empty());
  for (const gpu::BoxFace& r : lists.rows)
    EXPECT_EQ(r.box % 8u / 4u, 0u) << r.box;  // z bit
}

}  // namespace
}  // namespace deformcd::collision
