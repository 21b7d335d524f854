// Distances between the primitives of a proximity pair, mirroring
// src/core/collision/primitive_distance.h line for line: the same float and double operations
// in the same order, so that the GL proximity search keeps exactly the pairs the CPU's keeps.
// Change both files together. The why (a float bound first, the exact distance in double) is in
// the C++ header.
//
// Every float and double is `precise` (no fused a * b + c, no reordered sums), and glm's dot,
// length, cross, min, max and clamp are written out as glm computes them: dot sums
// (x + y) + z, length is sqrt(dot(v, v)), min(a, b) is b < a ? b : a, max(a, b) is
// a < b ? b : a, clamp(x, lo, hi) is min(max(x, lo), hi). GLSL's own min / max differ only for
// NaN and signed zeros, but the mirror should not differ at all. Doubles are core GLSL since
// 4.00; their literals carry `lf` (a bare 1e-12 is a float, rounded to another value).
// Include after #version: #include "common/primitive_distance.glsl".
#include "common/exact_math.glsl"
#include "common/layout.glsl"

// glm::min, glm::max and glm::clamp on floats and on doubles.
float distance_min(float a, float b) { return b < a ? b : a; }
float distance_max(float a, float b) { return a < b ? b : a; }
float distance_clamp(float x, float lo, float hi) { return distance_min(distance_max(x, lo), hi); }
double distance_min(double a, double b) { return b < a ? b : a; }
double distance_max(double a, double b) { return a < b ? b : a; }
double distance_clamp(double x, double lo, double hi) {
  return distance_min(distance_max(x, lo), hi);
}

// glm::dot on doubles (exact_dot is the float one).
double exact_dot(dvec3 a, dvec3 b) {
  precise dvec3 t = a * b;
  precise double r = (t.x + t.y) + t.z;
  return r;
}

// glm::length on floats.
float exact_length(vec3 v) {
  precise float r = sqrt(exact_dot(v, v));
  return r;
}

// point_segment_distance2<double>: the squared distance from p to segment (a, b) (to a when the
// segment is degenerate).
double point_segment_distance2(dvec3 p, dvec3 a, dvec3 b) {
  precise dvec3 ab = b - a;
  precise double length2 = exact_dot(ab, ab);
  precise double t = 0.0lf;
  if (length2 > 0.0lf) {
    precise dvec3 ap = p - a;
    precise double unclamped = exact_dot(ap, ab) / length2;
    t = distance_clamp(unclamped, 0.0lf, 1.0lf);
  }
  precise dvec3 d = p - (a + t * ab);
  return exact_dot(d, d);
}

// point_triangle_distance2<double>: the nearest of the three edges, or, when p's projection on
// the plane falls inside the triangle, of that projection.
double point_triangle_distance2(dvec3 p, dvec3 a, dvec3 b, dvec3 c) {
  precise double distance2 =
      distance_min(point_segment_distance2(p, a, b),
                   distance_min(point_segment_distance2(p, b, c), point_segment_distance2(p, c, a)));
  precise dvec3 ab = b - a, ac = c - a, ap = p - a;
  precise double d00 = exact_dot(ab, ab), d01 = exact_dot(ab, ac), d11 = exact_dot(ac, ac);
  precise double d20 = exact_dot(ap, ab), d21 = exact_dot(ap, ac);
  precise double denominator = d00 * d11 - d01 * d01;
  if (denominator > 0.0lf) {
    precise double v = (d11 * d20 - d01 * d21) / denominator;
    precise double w = (d00 * d21 - d01 * d20) / denominator;
    if (v >= 0.0lf && w >= 0.0lf && v + w <= 1.0lf) {
      precise dvec3 d = ap - (v * ab + w * ac);
      distance2 = distance_min(distance2, exact_dot(d, d));
    }
  }
  return distance2;
}

// segment_closest_parameters<float>: (s, t) of the closest points a0 + s (a1 - a0) and
// b0 + t (b1 - b0) of two segments, each in [0, 1]; false when either segment is degenerate.
// (The contact response's edge-edge geometry uses it too.)
bool segment_closest_parameters(vec3 a0, vec3 a1, vec3 b0, vec3 b1, out float s, out float t) {
  s = 0.0;
  t = 0.0;
  precise vec3 da = a1 - a0, db = b1 - b0, r = a0 - b0;
  precise float aa = exact_dot(da, da), bb = exact_dot(db, db), ab = exact_dot(da, db);
  precise float ar = exact_dot(da, r), br = exact_dot(db, r);
  if (!(aa > 0.0) || !(bb > 0.0)) return false;
  precise float denominator = aa * bb - ab * ab;
  precise float threshold = 1e-12 * aa * bb;
  // Parallel segments: any s works; take the one of a0 and let t and then s clamp.
  precise float ss = 0.0;
  if (denominator > threshold) {
    precise float unclamped = (ab * br - bb * ar) / denominator;
    ss = distance_clamp(unclamped, 0.0, 1.0);
  }
  precise float tt = (ab * ss + br) / bb;
  if (tt < 0.0) {
    tt = 0.0;
    precise float unclamped = -ar / aa;
    ss = distance_clamp(unclamped, 0.0, 1.0);
  } else if (tt > 1.0) {
    tt = 1.0;
    precise float unclamped = (ab - ar) / aa;
    ss = distance_clamp(unclamped, 0.0, 1.0);
  }
  s = ss;
  t = tt;
  return true;
}

// segment_closest_parameters<double>, the same lines on doubles.
bool segment_closest_parameters(dvec3 a0, dvec3 a1, dvec3 b0, dvec3 b1, out double s,
                                out double t) {
  s = 0.0lf;
  t = 0.0lf;
  precise dvec3 da = a1 - a0, db = b1 - b0, r = a0 - b0;
  precise double aa = exact_dot(da, da), bb = exact_dot(db, db), ab = exact_dot(da, db);
  precise double ar = exact_dot(da, r), br = exact_dot(db, r);
  if (!(aa > 0.0lf) || !(bb > 0.0lf)) return false;
  precise double denominator = aa * bb - ab * ab;
  precise double threshold = 1e-12lf * aa * bb;
  precise double ss = 0.0lf;
  if (denominator > threshold) {
    precise double unclamped = (ab * br - bb * ar) / denominator;
    ss = distance_clamp(unclamped, 0.0lf, 1.0lf);
  }
  precise double tt = (ab * ss + br) / bb;
  if (tt < 0.0lf) {
    tt = 0.0lf;
    precise double unclamped = -ar / aa;
    ss = distance_clamp(unclamped, 0.0lf, 1.0lf);
  } else if (tt > 1.0lf) {
    tt = 1.0lf;
    precise double unclamped = (ab - ar) / aa;
    ss = distance_clamp(unclamped, 0.0lf, 1.0lf);
  }
  s = ss;
  t = tt;
  return true;
}

// primitive_distance2: the squared distance between a pair's primitives, in double from their
// float coordinates: CONTACT_VERTEX_FACE, vertex x[0] and triangle (x[1], x[2], x[3]);
// CONTACT_EDGE_EDGE, segments (x[0], x[1]) and (x[2], x[3]) (a degenerate segment is a point).
double primitive_distance2(uint kind, vec3 x[4]) {
  const dvec3 y[4] = dvec3[4](dvec3(x[0]), dvec3(x[1]), dvec3(x[2]), dvec3(x[3]));
  if (kind != CONTACT_EDGE_EDGE) return point_triangle_distance2(y[0], y[1], y[2], y[3]);
  double s = 0.0lf, t = 0.0lf;
  if (!segment_closest_parameters(y[0], y[1], y[2], y[3], s, t)) {
    // A degenerate segment is a point (point_segment_distance2 takes a degenerate one too).
    return y[0] == y[1] ? point_segment_distance2(y[0], y[2], y[3])
                        : point_segment_distance2(y[2], y[0], y[1]);
  }
  precise dvec3 d = (y[0] + s * (y[1] - y[0])) - (y[2] + t * (y[3] - y[2]));
  return exact_dot(d, d);
}

// primitives_within: whether a pair's primitives, at x, can come within `reach` of each other
// while their distance shrinks by at most `closing`. First the float lower bound (the
// triangle's plane, or the segments' bounding spheres), then the exact squared distance in
// double against (reach + closing)^2 in double.
bool primitives_within(uint kind, vec3 x[4], float closing, float reach) {
  precise float limit_f = reach + closing;
  if (kind == CONTACT_EDGE_EDGE) {
    precise vec3 between = 0.5 * (x[0] + x[1]) - 0.5 * (x[2] + x[3]);
    precise float radii = 0.5 * (exact_length(x[1] - x[0]) + exact_length(x[3] - x[2]));
    precise float centres = exact_length(between);
    precise float gap = centres - radii;
    precise float bound = 1.001 * limit_f + 1e-5 * (centres + radii);
    if (gap > bound) return false;
  } else {
    precise vec3 normal = exact_cross(x[2] - x[1], x[3] - x[1]);
    precise float area2 = exact_length(normal);
    precise vec3 offset = x[0] - x[1];
    // glm::abs: x >= 0 ? x : -x (or fabsf); they and GLSL's abs differ only in a zero's sign,
    // which the comparison below does not see.
    precise float height = abs(exact_dot(offset, normal));
    precise float span = exact_length(offset);
    if (area2 > 0.0) {
      precise float bound = area2 * (1.001 * limit_f + 1e-5 * span);
      if (height > bound) return false;
    }
  }
  precise double limit = double(reach) + double(closing);
  precise double limit2 = limit * limit;
  return !(primitive_distance2(kind, x) > limit2);
}

// largest_per_side: the largest of a pair's per-vertex values on its first side (the vertex, or
// the first edge) plus the largest on its second.
float largest_per_side(uint kind, float value[4]) {
  const uint first_b = kind == CONTACT_EDGE_EDGE ? 2u : 1u;
  precise float side_a = 0.0, side_b = 0.0;
  for (uint k = 0u; k < 4u; ++k) {
    if (k < first_b) {
      side_a = distance_max(side_a, value[k]);
    } else {
      side_b = distance_max(side_b, value[k]);
    }
  }
  precise float total = side_a + side_b;
  return total;
}

// closing_speed: how fast a pair's distance can shrink when each vertex moves at m[k]: the
// fastest of one side's |m - mean| plus the fastest of the other's.
float closing_speed(uint kind, vec3 m[4]) {
  precise vec3 mean = ((m[0] + m[1]) + (m[2] + m[3])) * 0.25;
  float speed[4];
  for (uint k = 0u; k < 4u; ++k) speed[k] = exact_length(m[k] - mean);
  return largest_per_side(kind, speed);
}
