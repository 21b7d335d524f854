// The per-element steps of the broad phases, mirroring src/core/collision/broad_phase.h line
// for line, so that the GL and CPU backends take the same decisions on the same floats. Change
// both files together.
//
// An including shader that calls is_first_box_pair must define
//   bool mask_says_overlap(uint mask_slot, uint box_a, uint box_b);
// (the C++ template's `overlap(i, j)`): whether leaf box box_a of the mesh pair's mesh a and
// box_b of its mesh b overlap, read from the box mask of that mesh pair.
#include "common/layout.glsl"

// A box that contains nothing and overlaps nothing (a leaf box that lists no face). The value
// is FLT_MAX (std::numeric_limits<float>::max()), written out because GLSL has no constant for it.
Box empty_box() {
  const float big = 3.402823466e38;
  return Box(vec4(big, big, big, 0.0), vec4(-big, -big, -big, 0.0));
}

void grow_box(inout Box box, vec3 p) {
  box.min = vec4(min(box.min.xyz, p), 0.0);
  box.max = vec4(max(box.max.xyz, p), 0.0);
}

// Closed boxes: touching counts as overlapping, since touching triangles intersect.
bool boxes_overlap(Box a, Box b) {
  return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y &&
         a.min.z <= b.max.z && b.min.z <= a.max.z;
}

// Whether bit `box` (0-63) of a face's leaf-box set is set.
bool has_box(uvec2 boxes, uint box) {
  return ((boxes[box / 32u] >> (box % 32u)) & 1u) != 0u;
}

bool mask_says_overlap(uint mask_slot, uint box_a, uint box_b);

// A face pair listed under several box pairs must be tested and reported once: only from the
// first box pair (box_a, box_b), in lexicographic order, among the pairs listing both faces
// whose boxes overlap (see broad_phase.h).
bool is_first_box_pair(uvec2 boxes_a, uvec2 boxes_b, uint box_a, uint box_b, uint mask_slot) {
  for (uint wa = 0u; wa < 2u; ++wa) {
    uint bits_a = boxes_a[wa];
    while (bits_a != 0u) {
      const uint i = 32u * wa + uint(findLSB(bits_a));
      bits_a &= bits_a - 1u;
      if (i > box_a) return true;
      for (uint wb = 0u; wb < 2u; ++wb) {
        uint bits_b = boxes_b[wb];
        while (bits_b != 0u) {
          const uint j = 32u * wb + uint(findLSB(bits_b));
          bits_b &= bits_b - 1u;
          if ((i < box_a || j < box_b) && mask_says_overlap(mask_slot, i, j)) return false;
        }
      }
    }
  }
  return true;
}
