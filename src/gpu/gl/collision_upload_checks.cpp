#include "collision_upload_checks.h"

#include <string>

#include "core/collision/broad_phase.h"
#include "deformcd/error.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::gl {

namespace {

using std::to_string;

[[noreturn]] void inconsistent(const std::string& what) {
  throw Error("WorldState is inconsistent: " + what);
}

void check_faces(const WorldState& w) {
  for (std::size_t f = 0; f < w.faces.size(); ++f) {
    const gpu::Face& face = w.faces[f];
    for (std::uint32_t n : {face.a, face.b, face.c}) {
      if (n >= w.node_count()) {
        inconsistent("face " + to_string(f) + " has node " + to_string(n) + ", but there are " +
                     to_string(w.node_count()) + " nodes");
      }
    }
  }
}

// Object b's faces and rows lie inside the arrays, and its leaf boxes are 64 b .. 64 b + 63
// (the shaders index boxes by body, without reading box_offset).
void check_object(const WorldState& w, std::uint32_t b) {
  const gpu::ObjectInfo& o = w.objects[b];
  const std::string name = "object " + to_string(b);
  if (std::uint64_t{o.face_offset} + o.face_count > w.faces.size()) {
    inconsistent(name + "'s faces [" + to_string(o.face_offset) + ", +" + to_string(o.face_count) +
                 ") reach past the " + to_string(w.faces.size()) + " faces");
  }
  if (std::uint64_t{o.box_face_offset} + o.box_face_count > w.box_faces.size()) {
    inconsistent(name + "'s box-face rows [" + to_string(o.box_face_offset) + ", +" +
                 to_string(o.box_face_count) + ") reach past the " + to_string(w.box_faces.size()) +
                 " rows");
  }
  if (o.box_offset != gpu::kLeafBoxesPerBody * b || o.box_count != gpu::kLeafBoxesPerBody) {
    inconsistent(name + " has leaf boxes [" + to_string(o.box_offset) + ", +" +
                 to_string(o.box_count) + "), not the 64 from " +
                 to_string(gpu::kLeafBoxesPerBody * b));
  }
}

// Leaf box k of object b lists rows of that object only, each naming box k and a face of the
// object whose face_boxes has bit k (the narrow phase's deduplication reads those bits).
void check_box_rows(const WorldState& w, std::uint32_t b) {
  const gpu::ObjectInfo& o = w.objects[b];
  for (std::uint32_t k = 0; k < gpu::kLeafBoxesPerBody; ++k) {
    const glm::uvec2 rows = w.box_rows[gpu::kLeafBoxesPerBody * b + k];
    const std::string box = "leaf box " + to_string(k) + " of object " + to_string(b);
    if (rows.x < o.box_face_offset ||
        std::uint64_t{rows.x} + rows.y > std::uint64_t{o.box_face_offset} + o.box_face_count) {
      inconsistent(box + " has rows [" + to_string(rows.x) + ", +" + to_string(rows.y) +
                   ") outside its object's [" + to_string(o.box_face_offset) + ", +" +
                   to_string(o.box_face_count) + ")");
    }
    for (std::uint32_t r = rows.x; r < rows.x + rows.y; ++r) {
      const gpu::BoxFace& row = w.box_faces[r];
      if (row.box != k || row.face < o.face_offset || row.face - o.face_offset >= o.face_count) {
        inconsistent(box + ": row " + to_string(r) + " names box " + to_string(row.box) +
                     " and face " + to_string(row.face) + ", not box " + to_string(k) +
                     " and a face of the object");
      }
      if (!collision::has_box(w.face_boxes[row.face], k)) {
        inconsistent(box + " lists face " + to_string(row.face) +
                     ", but the face's face_boxes lacks bit " + to_string(k));
      }
    }
  }
}

void check_body_pairs(const WorldState& w) {
  for (std::size_t p = 0; p < w.body_pairs.size(); ++p) {
    const gpu::BodyPair pair = w.body_pairs[p];
    if (!(pair.a < pair.b && pair.b < w.body_count())) {
      inconsistent("body pair " + to_string(p) + " is (" + to_string(pair.a) + ", " +
                   to_string(pair.b) + "), not a < b < " + to_string(w.body_count()));
    }
  }
}

template <class T>
BufferSize size_of(std::string_view name, gpu::Binding binding, std::uint64_t count) {
  return {name, binding, count, sizeof(T)};
}

}  // namespace

std::vector<BufferSize> collision_buffer_sizes(const WorldState& w, std::uint64_t pair_capacity,
                                               std::uint64_t mask_slots) {
  constexpr std::uint64_t kMaskEntries = gpu::kLeafBoxesPerBody * gpu::kLeafBoxesPerBody;
  return {
      size_of<gpu::Box>("BoundingBox Information", gpu::kBoxInfo,
                        gpu::kLeafBoxesPerBody * w.body_count()),
      size_of<std::uint32_t>("BoundingBox Collision Result", gpu::kCollisionResult, w.faces.size()),
      size_of<gpu::Face>("Face Information", gpu::kFaceInfo, w.faces.size()),
      size_of<gpu::ObjectInfo>("Object Information", gpu::kObjectInfo, w.objects.size()),
      size_of<gpu::BoxFace>("BoundingBox Face List", gpu::kBoxFaceList, w.box_faces.size()),
      size_of<gpu::FacePair>("Face Pair", gpu::kFacePair, pair_capacity),
      size_of<std::int32_t>("BoundingBox Mask", gpu::kBoxMask, mask_slots * kMaskEntries),
      size_of<glm::uvec2>("Face Boxes", gpu::kFaceBoxes, w.face_boxes.size()),
      size_of<gpu::BodyPair>("Body Pair", gpu::kBodyPair, w.body_pairs.size()),
      size_of<gpu::CollisionCounters>("Collision Counters", gpu::kCollisionCounters, 1),
      size_of<glm::uvec2>("Box Rows", gpu::kBoxRows, w.box_rows.size()),
  };
}

void check_collision_consistency(const WorldState& w) {
  if (w.face_boxes.size() != w.faces.size()) {
    inconsistent("face_boxes has " + to_string(w.face_boxes.size()) + " entries, but faces has " +
                 to_string(w.faces.size()));
  }
  if (w.box_rows.size() != gpu::kLeafBoxesPerBody * w.body_count()) {
    inconsistent("box_rows has " + to_string(w.box_rows.size()) + " entries, but " +
                 to_string(w.body_count()) + " bodies call for " +
                 to_string(gpu::kLeafBoxesPerBody * w.body_count()));
  }
  check_faces(w);
  for (std::uint32_t b = 0; b < w.body_count(); ++b) {
    check_object(w, b);
    check_box_rows(w, b);
  }
  check_body_pairs(w);
}

}  // namespace deformcd::gl
