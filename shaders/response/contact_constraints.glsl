// Contact response as per-element functions, mirroring src/core/response/contact_constraints.h
// line for line: the same float operations in the same order, so that the GL and CPU backends
// compute the same bits (tests/gl/gl_contact_response_test.cpp checks it). Change both files
// together. The why of the method (Gauss-Seidel sweeps in colours, the contacts mass split,
// Coulomb friction, restitution) is in the C++ header. The compaction and count passes
// (response/contact_compact.comp, contact_count.comp) list the acting constraints and each
// node's active slots; the CPU builds the same lists on the host. The sweep's order (colour by
// colour) is the host's (src/core/response/sweep_order.h), for both backends.
//
// Every float is `precise`: without it the driver may fuse a * b + c into one fma (one rounding
// instead of two) or reorder sums, and the results would drift from the C++ ones by an ulp here
// and there, which a few substeps of sweeps amplify. dot, cross and the min / max of
// glm are written out for the same reason (glm::dot sums (x + y) + z; glm::max(a, b) is
// a < b ? b : a, which differs from GLSL's max only for NaN and signed zeros, but the mirror
// should not differ at all). segment_closest_parameters, which the edge-edge geometry uses, those
// written-out min / max / clamp (distance_min, distance_max, distance_clamp) and the side rule
// of a pair's nodes (largest_per_side) are common/primitive_distance.glsl's (the proximity
// search uses them too).
#include "common/exact_math.glsl"
#include "common/layout.glsl"
#include "common/primitive_distance.glsl"
#include "sim/mass_spring.glsl"

// Per-substep constants (response::ContactConstants).
struct ContactConstants {
  float h;                  // substep length, s
  float friction_static;    // Coulomb static coefficient (>= 0)
  float friction_dynamic;   // Coulomb dynamic coefficient (>= 0, <= friction_static)
  float restitution;        // 0: the approach speed is absorbed, 1: given back along n
  float max_untangle_step;  // m: most an untangling constraint moves its nodes per substep
  float elapsed;            // s: from the frame's start to the end of this substep
};

// slid_before's answers (response::kNoneSlid, kSomeSlid, kAllSlid).
const uint NONE_SLID = 0u;
const uint SOME_SLID = 1u;
const uint ALL_SLID = 2u;


// plane_barycentric: the closest point of the plane projection of p on triangle (a, b, c) as
// barycentric weights (u, v, w), u + v + w = 1 (not clamped here); false for a degenerate
// triangle.
bool plane_barycentric(vec3 p, vec3 a, vec3 b, vec3 c, out vec3 uvw) {
  uvw = vec3(0.0);
  precise vec3 ab = b - a, ac = c - a, ap = p - a;
  precise float d00 = exact_dot(ab, ab), d01 = exact_dot(ab, ac), d11 = exact_dot(ac, ac);
  precise float d20 = exact_dot(ap, ab), d21 = exact_dot(ap, ac);
  precise float denominator = d00 * d11 - d01 * d01;
  precise float threshold = 1e-12 * d00 * d11;
  if (!(denominator > threshold)) return false;
  precise float v = (d11 * d20 - d01 * d21) / denominator;
  precise float w = (d00 * d21 - d01 * d20) / denominator;
  precise vec3 result = vec3(1.0 - v - w, v, w);
  uvw = result;
  return true;
}

// edge_line_side, line for line: which side of edge (x[2], x[3])'s line edge (x[0], x[1])'s
// line passes on (the sign of (x[0] - x[2]) . (da x db)), 0 where the edges are within about 6
// degrees of parallel. (edge_edge_start_side is the host's alone.)
float edge_line_side(vec3 x[4]) {
  precise vec3 da = x[1] - x[0], db = x[3] - x[2];
  precise vec3 normal = exact_cross(da, db);
  precise float normal2 = exact_dot(normal, normal);
  precise float parallel = 1e-2 * exact_dot(da, da) * exact_dot(db, db);
  if (!(normal2 > parallel)) return 0.0;
  precise float along = exact_dot(x[0] - x[2], normal);
  return along > 0.0 ? 1.0 : -1.0;
}

// edge_edge_side, line for line: edge_line_side where the closest points (s, t) are inside both
// edges, else 0.
float edge_edge_side(vec3 x[4], float s, float t) {
  if (!(s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0)) return 0.0;
  return edge_line_side(x);
}

// reads_window_start, line for line: whether contact_geometry reads the window's start (edge
// pairs with a side); the passes load it for those alone.
bool reads_window_start(ContactPair pair) {
  return pair.kind == CONTACT_EDGE_EDGE && pair.side != 0.0;
}

// edge_offset_along_the_way, line for line: the corners a share `tau` of the way from the
// window's start to now, into p; their lines' offset along da x db there.
float edge_offset_along_the_way(vec3 start[4], vec3 x[4], float tau, out vec3 p[4]) {
  for (int k = 0; k < 4; ++k) {
    precise vec3 moved = start[k] + tau * (x[k] - start[k]);
    p[k] = moved;
  }
  precise float offset = exact_dot(p[0] - p[2], exact_cross(p[1] - p[0], p[3] - p[2]));
  return offset;
}

const int THROUGH_BISECTIONS = 24;  // response::kThroughBisections

// edges_went_through, line for line: whether, where the edges' lines meet on the straight way
// from the window's start (offset sign `side`) to now (found by bisection), the meeting point
// is inside both edges and they are not parallel there.
bool edges_went_through(vec3 start[4], vec3 x[4], float side) {
  vec3 p[4];
  precise float before = 0.0, after = 1.0;
  for (int i = 0; i < THROUGH_BISECTIONS; ++i) {
    precise float middle = 0.5 * (before + after);
    precise float signed_offset = edge_offset_along_the_way(start, x, middle, p) * side;
    if (signed_offset > 0.0) {
      before = middle;
    } else {
      after = middle;
    }
  }
  edge_offset_along_the_way(start, x, after, p);
  float s = 0.0, t = 0.0;
  if (!segment_closest_parameters(p[0], p[1], p[2], p[3], s, t)) return false;
  return edge_edge_side(p, s, t) != 0.0;
}

// contact_geometry: normal n, weights b (sum 0) and C, the distance along n minus the thickness
// (the constraint wants C >= 0), on the current positions (the window's start: `start`, read
// only where reads_window_start says). False when the constraint does not apply now (vertex
// beside the face, beyond its band, degenerate).
bool contact_geometry(ContactPair pair, vec3 x[4], vec3 start[4], out vec3 n, out float b[4],
                      out float c) {
  n = vec3(0.0);
  b = float[4](0.0, 0.0, 0.0, 0.0);
  c = 0.0;
  if (pair.kind == CONTACT_EDGE_EDGE) {
    float s = 0.0, t = 0.0;
    if (!segment_closest_parameters(x[0], x[1], x[2], x[3], s, t)) return false;
    precise vec3 d = (x[0] + s * (x[1] - x[0])) - (x[2] + t * (x[3] - x[2]));
    precise float distance = sqrt(exact_dot(d, d));
    precise float crossing = 1e-7 * pair.thickness;
    if (!(distance > crossing)) return false;  // crossing: no direction
    precise vec3 unit = d / distance;
    n = unit;
    // Edges that went through each other since the window started: their distance counts as
    // negative, to the hold depth.
    if (pair.side != 0.0 && edge_edge_side(x, s, t) == -pair.side &&
        edges_went_through(start, x, pair.side)) {
      if (distance > distance_max(pair.thickness, pair.hold_depth)) return false;
      n = -n;
      distance = -distance;
    }
    precise float one_minus_s = 1.0 - s;
    precise float one_minus_t = 1.0 - t;
    b[0] = one_minus_s;
    b[1] = s;
    b[2] = -one_minus_t;
    b[3] = -t;
    precise float gap = distance - pair.thickness;
    c = gap;
    return true;
  }
  // Vertex x[0] against face (x[1], x[2], x[3]), along the face's outward normal.
  precise vec3 normal = exact_cross(x[2] - x[1], x[3] - x[1]);
  precise float area2 = sqrt(exact_dot(normal, normal));
  vec3 uvw = vec3(0.0);
  if (!(area2 > 0.0) || !plane_barycentric(x[0], x[1], x[2], x[3], uvw)) return false;
  precise vec3 unit = normal / area2;
  n = unit;
  precise float height = exact_dot(x[0] - x[1], unit);
  if (pair.kind == CONTACT_VERTEX_FACE) {
    // Only where the vertex lies over the face, started the window in front of it, and is not
    // deeper behind it than the hold depth (at least the thickness).
    if (uvw.x < 0.0 || uvw.y < 0.0 || uvw.z < 0.0) return false;
    if (!(pair.side > 0.0) || height < -max(pair.thickness, pair.hold_depth)) return false;
  } else {
    // Untangling (CONTACT_UNTANGLE): weights clamped into the face.
    precise vec3 clamped = vec3(distance_clamp(uvw.x, 0.0, 1.0), distance_clamp(uvw.y, 0.0, 1.0),
                                distance_clamp(uvw.z, 0.0, 1.0));
    precise float total = (clamped.x + clamped.y) + clamped.z;
    precise vec3 normalized = clamped / total;
    uvw = normalized;
  }
  b[0] = 1.0;
  b[1] = -uvw.x;
  b[2] = -uvw.y;
  b[3] = -uvw.z;
  precise float gap = height - pair.thickness;
  c = gap;
  return true;
}

// path_deviation, line for line: how far a node is from where the window's start carried along
// its path velocity puts it after `elapsed` seconds.
float path_deviation(vec3 position, vec4 frame_start, vec4 node_motion, float elapsed) {
  precise vec3 centre = frame_start.xyz + node_motion.xyz * elapsed;
  precise vec3 moved = position - centre;
  precise float deviation = sqrt(exact_dot(moved, moved));
  return deviation;
}

// projection_start, line for line: a node's position less h x its velocity (xyz), which only
// position corrections move, and its distance from its straight path (w).
vec4 projection_start(vec4 position, vec4 velocity, float h, vec4 frame_start, vec4 node_motion,
                      float elapsed) {
  precise vec3 base = position.xyz - h * velocity.xyz;
  return vec4(base, path_deviation(position.xyz, frame_start, node_motion, elapsed));
}

// contact_awake, line for line: whether the constraint may act `elapsed` seconds into its
// window, its nodes deviation[k] from their straight paths (a margin of 1e-4 of the thickness
// for rounding).
bool contact_awake(ContactPair pair, float deviation[4], float elapsed) {
  precise float closest = pair.gap - pair.closing_speed * elapsed;
  precise float margin = largest_per_side(pair.kind, deviation) + 1e-4 * pair.thickness;
  return !(closest > margin);
}

// abs_sum: the sum of the absolute values of v's components (at least its length).
float abs_sum(vec3 v) {
  precise float r = (abs(v.x) + abs(v.y)) + abs(v.z);
  return r;
}

// contact_clear, line for line: whether the primitives are surely farther apart than the
// thickness (the edges' lines' distance, or the vertex's height over the face's plane), with a
// margin beyond the rounding of this bound and of contact_geometry.
bool contact_clear(ContactPair pair, vec3 x[4]) {
  if (pair.kind == CONTACT_EDGE_EDGE) {
    precise vec3 da = x[1] - x[0], db = x[3] - x[2], r = x[0] - x[2];
    precise vec3 normal = exact_cross(da, db);
    precise float normal2 = exact_dot(normal, normal);
    precise float parallel = 1e-2 * exact_dot(da, da) * exact_dot(db, db);
    if (!(normal2 > parallel)) return false;
    precise float along = exact_dot(r, normal);
    precise float against = along * pair.side;
    if (against < 0.0) return false;  // maybe through each other: contact_geometry decides
    precise float limit =
        1.001 * pair.thickness + 1e-4 * abs_sum(r) + 1e-6 * (abs_sum(x[0]) + abs_sum(x[2]));
    precise float along2 = along * along;
    precise float bound = limit * limit * normal2;
    return along2 > bound;
  }
  precise vec3 normal = exact_cross(x[2] - x[1], x[3] - x[1]);
  precise vec3 offset = x[0] - x[1];
  precise float height = exact_dot(offset, normal);
  precise float limit = 1.001 * pair.thickness + 1e-4 * abs_sum(offset) + 1e-6 * abs_sum(x[1]);
  precise float height2 = height * height;
  precise float bound = limit * limit * exact_dot(normal, normal);
  return height > 0.0 && height2 > bound;
}

// contact_active, line for line: whether a contact acts now (its distance along n below its
// thickness).
bool contact_active(ContactPair pair, vec4 position[4], vec3 start[4]) {
  const vec3 x[4] = vec3[4](position[0].xyz, position[1].xyz, position[2].xyz, position[3].xyz);
  if (contact_clear(pair, x)) return false;
  vec3 n = vec3(0.0);
  float b[4] = float[4](0.0, 0.0, 0.0, 0.0);
  float c = 0.0;
  return contact_geometry(pair, x, start, n, b, c) && c < 0.0;
}

// guards_volumes, line for line: a self pair whose thickness the rest-distance rule cut.
bool guards_volumes(ContactPair pair) {
  return (pair.kind == CONTACT_VERTEX_FACE || pair.kind == CONTACT_EDGE_EDGE) &&
         pair.thickness < pair.hold_depth;
}

// kVolumeWatch and volume_watched, line for line: whether a volume constraint acts now (below
// VOLUME_WATCH x its floor; a thin one also when a corner is guarded, or when it would be below
// the watch after a substep of its collapse).
const float VOLUME_WATCH = 2.0;
bool volume_watched(ContactPair pair, vec4 position[4], vec4 velocity[4], float h, bool guarded) {
  const bool thin = pair.side > 0.0;
  if (thin && guarded) return true;
  const vec3 x[4] = vec3[4](position[0].xyz, position[1].xyz, position[2].xyz, position[3].xyz);
  vec3 g[4];
  precise float volume = tetrahedron_volume(x, g);
  precise float rate = 0.0;
  if (thin) {
    for (int i = 0; i < 4; ++i) rate += exact_dot(g[i], velocity[i].xyz);
  }
  precise float reached = volume + h * distance_min(rate, 0.0);
  precise float watch = VOLUME_WATCH * pair.thickness;
  return reached < watch;
}

// kResidualShare and contact_violated, line for line: whether an active constraint flagged
// `converge` is still deeper than half its thickness (a volume constraint's tetrahedron below
// half its floor) after a projection's iterations (more iterations are due).
const float RESIDUAL_SHARE = 0.5;
bool contact_violated(ContactPair pair, vec4 position[4], vec3 start[4]) {
  if (!(pair.converge > 0.0)) return false;
  const vec3 x[4] = vec3[4](position[0].xyz, position[1].xyz, position[2].xyz, position[3].xyz);
  if (pair.kind == CONTACT_VOLUME) {
    vec3 g[4];
    return tetrahedron_volume(x, g) < RESIDUAL_SHARE * pair.thickness;
  }
  vec3 n = vec3(0.0);
  float b[4] = float[4](0.0, 0.0, 0.0, 0.0);
  float c = 0.0;
  return contact_geometry(pair, x, start, n, b, c) && c < -RESIDUAL_SHARE * pair.thickness;
}

// solve_volume, line for line: a volume constraint's corrections (the tetrahedron's collapse
// rate cancelled beyond the rate that brings it to its floor in one substep, the volume below
// its floor restored by position alone, along the gradient, each node weighing its inverse
// mass, no node moved more than step_limit in one iteration).
void solve_volume(ContactPair pair, vec4 position[4], vec4 velocity[4], ContactConstants k,
                  inout vec4 given[3], inout vec4 correction[8]) {
  const vec3 x[4] = vec3[4](position[0].xyz, position[1].xyz, position[2].xyz, position[3].xyz);
  vec3 g[4];
  precise float volume = tetrahedron_volume(x, g);
  precise float weight = 0.0;
  precise float rate = 0.0;
  precise float lever = 0.0;  // the largest w_k |g_k|
  for (int i = 0; i < 4; ++i) {
    precise float g2 = exact_dot(g[i], g[i]);
    weight += position[i].w * g2;
    rate += exact_dot(g[i], velocity[i].xyz);
    lever = distance_max(lever, position[i].w * sqrt(g2));
  }
  if (!(weight > 0.0)) return;  // every node fixed, or a tetrahedron collapsed to a point
  precise float room = distance_max(volume - pair.thickness, 0.0) / k.h;
  precise float speed = distance_max(given[0].x - rate - room, 0.0) - given[0].x;
  precise float push =
      distance_max(given[0].y - ((volume - pair.thickness) + speed * k.h), 0.0) - given[0].y;
  precise float move = lever * abs(speed * k.h + push) / weight;
  if (move > pair.step_limit) {
    precise float scale = pair.step_limit / move;
    speed *= scale;
    push *= scale;
  }
  given[0].x += speed;
  given[0].y += push;
  for (int i = 0; i < 4; ++i) {
    precise float share = position[i].w / weight;
    precise vec3 dv = (share * speed) * g[i];
    precise vec3 dx = dv * k.h + (share * push) * g[i];
    correction[2 * i] = vec4(dx, 0.0);
    correction[2 * i + 1] = vec4(dv, 0.0);
  }
}

// solve_contact, line for line: corrections of the four nodes into correction[2 k] (position
// change) and correction[2 k + 1] (velocity change), a contact's nodes weighing by mass
// splitting (count[k] x inverse mass; a volume constraint reads no count). The approach velocity is cancelled (restitution x the first
// iteration's approach given back), moving the nodes by that change x h; the depth left is
// removed by position alone (an untangling constraint by at most max_untangle_step per
// iteration); Coulomb friction on the tangential relative velocity. `given` carries the normal
// speed (given[0].x) and push (y) given over the substep's iterations so far and the first
// iteration's approach (z), and the friction given (given[1].xyz, a vector) and the first
// iteration's slip (given[1].w), whether the first iteration's friction left the static cone
// (given[2].w); each iteration corrects the totals, the normal ones clamped at
// zero, the friction to its cone of the accumulated normal change; a sticking contact's hold
// (given[2].xyz) takes back the tangential drift position corrections gave its point since the
// projection's start (`start`), within the static cone of the push; `window_start`: where the
// nodes started the window (contact_geometry's `start`). `history` (slid_before):
// none, some or all of its free nodes slid in the last substep (all: it slid through it); the
// last iteration's slide flag goes to the w of each corner's velocity correction.
void solve_contact(ContactPair pair, vec4 position[4], vec4 velocity[4], uint count[4],
                   vec4 start[4], vec3 window_start[4], ContactConstants k, bool first_iteration,
                   bool last_iteration, uint history, inout vec4 given[3],
                   out vec4 correction[8]) {
  for (int i = 0; i < 8; ++i) correction[i] = vec4(0.0);
  if (first_iteration) {
    given[0] = vec4(0.0);
    given[1] = vec4(0.0);
    given[2] = vec4(0.0);
  }
  if (pair.kind == CONTACT_VOLUME) {
    solve_volume(pair, position, velocity, k, given, correction);
    return;
  }
  const vec3 x[4] = vec3[4](position[0].xyz, position[1].xyz, position[2].xyz, position[3].xyz);
  vec3 n = vec3(0.0);
  float b[4] = float[4](0.0, 0.0, 0.0, 0.0);
  float c = 0.0;
  if (!contact_geometry(pair, x, window_start, n, b, c)) return;
  precise float weight = 0.0;
  precise vec3 relative_velocity = vec3(0.0);
  precise vec3 drift = vec3(0.0);  // how far position corrections carried the contact point
  for (int i = 0; i < 4; ++i) {
    weight += float(count[i]) * position[i].w * b[i] * b[i];
    relative_velocity += b[i] * velocity[i].xyz;
    drift += b[i] * ((x[i] - k.h * velocity[i].xyz) - start[i].xyz);
  }
  if (!(weight > 0.0)) return;  // every node fixed
  precise float reduce = 1.0;  // no node moves more than 10 x its share of the correction
  for (int i = 0; i < 4; ++i) {
    precise float lever = float(count[i]) * position[i].w * abs(b[i]);
    if (lever > 10.0 * weight) reduce = distance_min(reduce, 10.0 * weight / lever);
  }
  precise float normal_velocity = exact_dot(relative_velocity, n);
  if (first_iteration) given[0].z = distance_max(-normal_velocity, 0.0);
  precise float total_speed =
      distance_max(given[0].x + (k.restitution * given[0].z - normal_velocity) * reduce, 0.0);
  precise float normal_speed = total_speed - given[0].x;
  given[0].x = total_speed;
  precise float total_push = distance_max(given[0].y - (c + normal_speed * k.h) * reduce, 0.0);
  if (pair.kind == CONTACT_UNTANGLE)
    total_push = distance_min(total_push, given[0].y + k.max_untangle_step);
  precise float push = total_push - given[0].y;
  given[0].y = total_push;
  // Coulomb friction as a vector total over the substep's iterations (given[1].xyz), clamped at
  // every iteration to the cone of the accumulated normal change (given[0].x): friction_dynamic's
  // for a contact that slid through the last substep, which slides on while its first
  // iteration's slip is more than friction_static's cone; for a sticking one friction_static's
  // until the last iteration, which takes friction_dynamic's where the first iteration's
  // wanted friction left friction_static's cone and half or more of its slip (given[1].w) is
  // left.
  precise vec3 tangential = relative_velocity - normal_velocity * n;
  precise vec3 before = given[1].xyz;
  precise vec3 held = before - exact_dot(before, n) * n;  // in the tangent plane of now
  precise vec3 wanted = held - reduce * tangential;      // the total that stops the slip
  precise float wanted_length = sqrt(exact_dot(wanted, wanted));
  precise float slip_left = reduce * sqrt(exact_dot(tangential, tangential));
  if (first_iteration) given[1].w = slip_left;
  precise float static_cone = k.friction_static * given[0].x;
  float overflowed = given[2].w;  // 1: the first iteration's friction left the static cone
  if (first_iteration) overflowed = wanted_length > static_cone ? 1.0 : 0.0;
  precise float half_first = 0.5 * given[1].w;
  const bool was_sliding = history == ALL_SLID;
  const bool starts_sliding =
      !was_sliding && last_iteration && overflowed > 0.0 && slip_left > half_first;
  const bool dynamic = was_sliding || starts_sliding;
  precise float coefficient = dynamic ? k.friction_dynamic : k.friction_static;
  precise float limit = coefficient * given[0].x;
  precise vec3 friction_total = wanted;
  if (wanted_length > limit) {
    precise float scale = limit / wanted_length;
    friction_total = wanted * scale;
  }
  const bool slides = starts_sliding || (was_sliding && given[1].w > static_cone);
  given[1] = vec4(friction_total, given[1].w);
  precise vec3 friction = friction_total - held;
  // The hold: a sticking contact none of whose free nodes slid in the last substep takes back
  // its point's tangential drift, within friction_static's cone of the push.
  precise vec3 drift_tangential = drift - exact_dot(drift, n) * n;
  precise vec3 before_hold = given[2].xyz;
  precise vec3 held_hold = before_hold - exact_dot(before_hold, n) * n;
  precise vec3 hold_total = vec3(0.0);
  if (!dynamic && history == NONE_SLID) {
    precise vec3 wanted_hold = held_hold - reduce * drift_tangential;
    precise float wanted_hold_length = sqrt(exact_dot(wanted_hold, wanted_hold));
    precise float hold_limit = k.friction_static * given[0].y;
    hold_total = wanted_hold;
    if (wanted_hold_length > hold_limit) {
      precise float hold_scale = hold_limit / wanted_hold_length;
      hold_total = wanted_hold * hold_scale;
    }
  }
  given[2] = vec4(hold_total, overflowed);
  precise vec3 hold = hold_total - held_hold;
  precise vec3 dv = (normal_speed * n + friction) / weight;
  precise vec3 dx = dv * k.h + (push / weight) * n + hold / weight;
  const float slide_flag = last_iteration && slides ? 1.0 : 0.0;
  for (int i = 0; i < 4; ++i) {
    precise float scale = position[i].w * b[i];
    precise vec3 move = scale * dx;
    precise vec3 speed = scale * dv;
    correction[2 * i] = vec4(move, 0.0);
    correction[2 * i + 1] = vec4(speed, slide_flag);
  }
}

// slid_before, line for line: how many of the contact's free nodes had a contact slide in the
// substep before projection `substep`: none, some or all.
uint slid_before(vec4 position[4], uint slid[4], uint substep) {
  uint free_nodes = 0u;
  uint slid_nodes = 0u;
  for (int i = 0; i < 4; ++i) {
    if (!(position[i].w > 0.0)) continue;
    ++free_nodes;
    if (slid[i] + 1u == substep) ++slid_nodes;
  }
  if (slid_nodes == 0u) return NONE_SLID;
  return slid_nodes == free_nodes ? ALL_SLID : SOME_SLID;
}

// apply_correction, line for line: the corrections move the position and the velocity. Fixed
// nodes are left alone.
void apply_correction(inout vec4 position, inout vec4 velocity, vec3 dx, vec3 dv) {
  if (!(position.w > 0.0)) return;
  precise vec3 p = position.xyz + dx;
  precise vec3 v = velocity.xyz + dv;
  velocity = vec4(v, 0.0);
  position = vec4(p, position.w);
}

// beyond_reach, line for line: a free node `deviation` from its straight path has strayed
// beyond its reach (frame_start.w).
bool beyond_reach(float deviation, vec4 position, vec4 frame_start) {
  return position.w > 0.0 && deviation > frame_start.w;
}

// strayed, line for line: beyond_reach of a node at `position`, its deviation measured from its
// window-start position carried along its straight path (node_motion.xyz x elapsed).
bool strayed(vec4 position, vec4 frame_start, vec4 node_motion, float elapsed) {
  return beyond_reach(path_deviation(position.xyz, frame_start, node_motion, elapsed), position,
                      frame_start);
}
