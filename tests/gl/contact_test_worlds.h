#pragma once
// Worlds and constraint sets for the contact response tests: nodes placed by hand or at random
// (no springs, no tetrahedra: the response alone is under test), hand-made constraints that
// reach every branch of src/core/response/contact_constraints.h, random ones, and bitwise
// comparison of two node arrays.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/response/contact_constraints.h"
#include "core/response/frame_constraints.h"
#include "deformcd/gpu_layout.h"
#include "deformcd/simulation_state.h"

namespace deformcd::test {

/// Where each node starts the window (FrameConstraints::window_start): `positions`' xyz.
inline std::vector<glm::vec3> window_start_of(const std::vector<glm::vec4>& positions) {
  std::vector<glm::vec3> out;
  out.reserve(positions.size());
  for (const glm::vec4& x : positions)
    out.emplace_back(x);
  return out;
}

/// Each node's motion (FrameConstraints::node_motion) from its body's, `per_body`.
inline std::vector<glm::vec4> node_motion_of_bodies(const std::vector<glm::vec4>& per_body,
                                                    const std::vector<std::uint32_t>& node_body) {
  std::vector<glm::vec4> out;
  out.reserve(node_body.size());
  for (const std::uint32_t b : node_body)
    out.push_back(per_body[b]);
  return out;
}

/// A world of unconnected nodes (xyz, w = inverse mass) in `body_count` bodies.
inline SimulationState free_nodes(std::vector<glm::vec4> positions,
                                  std::vector<glm::vec4> velocities,
                                  std::vector<std::uint32_t> node_body, std::uint32_t body_count) {
  SimulationState w;
  const std::size_t n = positions.size();
  w.positions = std::move(positions);
  w.velocities = std::move(velocities);
  w.node_body = std::move(node_body);
  w.forces.assign(n, glm::vec4(0.0f));
  w.node_spring_offset.assign(n + 1, 0u);
  w.node_tet_offset.assign(n + 1, 0u);
  w.body_params.assign(body_count, gpu::BodyParams{glm::vec4(0.0f), 0.0f, 0.0f, 0.0f, 0.0f});
  for (std::uint32_t b = 0; b < body_count; ++b)
    w.body_names.push_back("body " + std::to_string(b));
  return w;
}

/// Components of xyzw whose bits differ between two equally long arrays (0: bit-identical,
/// signed zeros and NaN payloads included).
inline std::size_t bitwise_differences(const std::vector<glm::vec4>& a,
                                       const std::vector<glm::vec4>& b) {
  std::size_t differ = a.size() == b.size() ? 0 : 1;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i)
    for (int k = 0; k < 4; ++k)
      differ += std::memcmp(&a[i][k], &b[i][k], sizeof(float)) != 0 ? 1 : 0;
  return differ;
}

/// One scenario of the hand-made set: its constraints' first and last index, and whether the
/// CPU reference moves its nodes (so that the set provably reaches the branch it names).
struct ContactScenario {
  std::string name;
  std::uint32_t first_node = 0;
  std::uint32_t node_count = 0;
  bool moves = false;
};

struct HandMadeContacts {
  SimulationState world;
  response::FrameConstraints constraints;
  std::vector<ContactScenario> scenarios;
};

/// Every branch of the constraint functions, each scenario on nodes of its own, 1 m apart, so
/// that none disturbs another (except where sharing is the point). Thickness 0.01 m.
inline HandMadeContacts hand_made_contacts() {
  constexpr float kThickness = 0.01f;
  constexpr std::uint32_t kVertexFaceFromBehind = 100u;  // a vf pair with side 0
  // A vf pair whose thickness is a quarter of kThickness, holding to kThickness behind the face
  // (ContactPair::hold_depth, as a self pair the rest-distance rule cut).
  constexpr std::uint32_t kVertexFaceHeldDeep = 101u;
  HandMadeContacts out;
  std::vector<glm::vec4> x, v;
  std::vector<std::uint32_t> body;
  float slot = 0.0f;
  // Adds a scenario: `nodes` placed around (slot, 0, 0), inverse masses w, velocities vel,
  // constraints over local node indices.
  const auto add = [&](const std::string& name, const std::vector<glm::vec3>& nodes,
                       const std::vector<float>& w, const std::vector<glm::vec3>& vel,
                       const std::vector<std::pair<std::uint32_t, glm::uvec4>>& pairs, bool moves,
                       std::uint32_t body_of_nodes = 0) {
    const auto first = static_cast<std::uint32_t>(x.size());
    const glm::vec3 origin(slot, 0.0f, 0.0f);
    slot += 1.0f;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      x.emplace_back(origin + nodes[i], w[i]);
      v.emplace_back(vel.empty() ? glm::vec3(0.0f) : vel[i], 0.0f);
      body.push_back(body_of_nodes);
    }
    for (const auto& [kind, local] : pairs) {
      gpu::ContactPair p{};
      for (int k = 0; k < 4; ++k)
        p.nodes[k] = first + local[k];
      // kVertexFaceFromBehind: a vertex-face constraint whose vertex started behind the face.
      const bool held_deep = kind == kVertexFaceHeldDeep;
      p.kind = kind == kVertexFaceFromBehind || held_deep ? gpu::kContactVertexFace : kind;
      p.side = kind == gpu::kContactVertexFace || held_deep ? 1.0f : 0.0f;
      p.thickness = held_deep ? 0.25f * kThickness : kThickness;
      if (held_deep) p.hold_depth = kThickness;
      out.constraints.pairs.push_back(p);
    }
    out.scenarios.push_back({name, first, static_cast<std::uint32_t>(nodes.size()), moves});
  };
  // A face in z = 0 around the origin, counter-clockwise seen from +z (normal +z).
  const glm::vec3 f0(-0.1f, -0.1f, 0.0f), f1(0.1f, -0.1f, 0.0f), f2(0.0f, 0.1f, 0.0f);
  const std::vector<float> free4 = {1.0f, 2.0f, 0.5f, 1.0f};
  const std::uint32_t vf = gpu::kContactVertexFace, ee = gpu::kContactEdgeEdge,
                      un = gpu::kContactUntangle;
  const glm::uvec4 v_on_f(0, 1, 2, 3);

  add("vertex-face, above within the thickness", {{0.01f, 0.0f, 0.004f}, f0, f1, f2}, free4, {},
      {{vf, v_on_f}}, true);
  add("vertex-face, above beyond the thickness", {{0.0f, 0.0f, 0.05f}, f0, f1, f2}, free4, {},
      {{vf, v_on_f}}, false);
  add("vertex-face, below within the thickness", {{0.0f, -0.02f, -0.006f}, f0, f1, f2}, free4, {},
      {{vf, v_on_f}}, true);
  add("vertex-face, below deeper than the thickness", {{0.0f, 0.0f, -0.03f}, f0, f1, f2}, free4, {},
      {{vf, v_on_f}}, false);
  add("vertex-face, below deeper than its thickness, within its hold depth",
      {{0.0f, 0.0f, -0.006f}, f0, f1, f2}, free4, {}, {{kVertexFaceHeldDeep, v_on_f}}, true);
  add("vertex-face, below within the thickness, started behind",
      {{0.0f, -0.02f, -0.006f}, f0, f1, f2}, free4, {}, {{kVertexFaceFromBehind, v_on_f}}, false);
  add("vertex-face, beside the face", {{0.3f, 0.0f, 0.002f}, f0, f1, f2}, free4, {}, {{vf, v_on_f}},
      false);
  add("vertex-face, degenerate (collinear) face",
      {{0.0f, 0.0f, 0.002f}, f0, f1, {0.0f, -0.1f, 0.0f}}, free4, {}, {{vf, v_on_f}}, false);
  add("vertex-face, face fixed (inverse mass 0)", {{0.02f, 0.01f, 0.003f}, f0, f1, f2},
      {1.0f, 0.0f, 0.0f, 0.0f}, {}, {{vf, v_on_f}}, true);
  add("vertex-face, every node fixed", {{0.0f, 0.0f, 0.003f}, f0, f1, f2}, {0.0f, 0.0f, 0.0f, 0.0f},
      {}, {{vf, v_on_f}}, false);
  add("edge-edge, crossing within the thickness",
      {{-0.1f, 0.01f, 0.003f}, {0.1f, 0.0f, 0.003f}, {0.02f, -0.1f, 0.0f}, {0.0f, 0.1f, 0.0f}},
      free4, {}, {{ee, v_on_f}}, true);
  add("edge-edge, crossing exactly (no direction)",
      {{-0.1f, 0.0f, 0.0f}, {0.1f, 0.0f, 0.0f}, {0.0f, -0.1f, 0.0f}, {0.0f, 0.1f, 0.0f}}, free4, {},
      {{ee, v_on_f}}, false);
  add("edge-edge, parallel and overlapping",
      {{-0.1f, 0.0f, 0.0f}, {0.1f, 0.0f, 0.0f}, {-0.05f, 0.004f, 0.001f}, {0.15f, 0.004f, 0.001f}},
      free4, {}, {{ee, v_on_f}}, true);
  add("edge-edge, closest at an end (t clamped)",
      {{-0.1f, 0.0f, 0.0f}, {0.1f, 0.0f, 0.0f}, {0.05f, 0.005f, 0.0f}, {0.05f, 0.2f, 0.003f}},
      free4, {}, {{ee, v_on_f}}, true);
  add("edge-edge, degenerate edge",
      {{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {-0.1f, 0.002f, 0.0f}, {0.1f, 0.002f, 0.0f}}, free4,
      {}, {{ee, v_on_f}}, false);
  add("untangle, deep (step bounded)", {{0.01f, 0.01f, -0.2f}, f0, f1, f2}, free4, {},
      {{un, v_on_f}}, true);
  add("untangle, beside the face (weights clamped)", {{0.4f, 0.3f, -0.05f}, f0, f1, f2}, free4, {},
      {{un, v_on_f}}, true);
  // One vertex under a fan of four faces around it, sharing their nodes: counts of 4 and 2.
  add("shared nodes, a vertex under a fan of faces",
      {{0.0f, 0.0f, -0.003f},
       {0.0f, 0.0f, 0.0f},
       {0.1f, 0.0f, 0.0f},
       {0.0f, 0.1f, 0.0f},
       {-0.1f, 0.0f, 0.0f},
       {0.0f, -0.1f, 0.0f},
       {0.03f, 0.03f, -0.004f}},
      {1.0f, 1.0f, 1.0f, 0.5f, 2.0f, 1.0f, 1.0f}, {},
      {{vf, {0, 1, 2, 3}},
       {vf, {0, 1, 3, 4}},
       {vf, {0, 1, 4, 5}},
       {vf, {0, 1, 5, 2}},
       {vf, {6, 1, 2, 3}},
       {un, {0, 2, 3, 4}}},
      true);
  // An edge-edge constraint over-corrects the light end of an edge whose heavy end a vertex-face
  // constraint also stops: the later iterations take the excess back (solve_contact's totals).
  add("lever, a light node's edge on a fixed edge, its heavy end on a fixed face",
      {{0.0f, 0.02f, 0.009f},
       {0.0f, -0.06f, 0.009f},
       {-0.1f, 0.0f, 0.0f},
       {0.1f, 0.0f, 0.0f},
       {-0.1f, -0.12f, 0.0f},
       {0.1f, -0.12f, 0.0f},
       {0.0f, 0.0f, 0.0f}},
      {100.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f},
      {{0.0f, 0.0f, -1.0f},
       {0.0f, 0.0f, -1.0f},
       {0.0f, 0.0f, 0.0f},
       {0.0f, 0.0f, 0.0f},
       {0.0f, 0.0f, 0.0f},
       {0.0f, 0.0f, 0.0f},
       {0.0f, 0.0f, 0.0f}},
      {{ee, {0, 1, 2, 3}}, {vf, {1, 4, 5, 6}}}, true);
  // Friction: the same approach with a small slip (static: the tangential velocity is taken
  // out entirely) and a large one (dynamic: reduced by friction_dynamic x the normal speed).
  add("friction, static", {{0.0f, 0.0f, 0.005f}, f0, f1, f2}, free4,
      {{0.05f, 0.0f, -1.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}},
      {{vf, v_on_f}}, true);
  add("friction, dynamic", {{0.0f, 0.0f, 0.005f}, f0, f1, f2}, free4,
      {{40.0f, 10.0f, -1.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}},
      {{vf, v_on_f}}, true);
  add("restitution, head-on approach", {{0.0f, 0.0f, 0.009f}, f0, f1, f2}, free4,
      {{0.0f, 0.0f, -3.0f}, {0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 1.0f}},
      {{vf, v_on_f}}, true);
  // Body 1's reach is small: the push takes the vertex beyond it, and a new search is due.
  add("beyond the reach (body 1)", {{0.0f, 0.0f, -0.009f}, f0, f1, f2}, free4, {}, {{vf, v_on_f}},
      true, 1);

  out.world = free_nodes(std::move(x), std::move(v), std::move(body), 2);
  out.constraints.node_motion = node_motion_of_bodies(
      {glm::vec4(0.0f, 0.0f, 0.0f, 0.5f), glm::vec4(0.0f, 0.0f, 0.0f, 0.002f)},
      out.world.node_body);
  out.constraints.window_start = window_start_of(out.world.positions);
  return out;
}

struct RandomContacts {
  SimulationState world;
  response::FrameConstraints constraints;
};

/// Two edges, one edge-edge constraint (thickness 0.01 m), that one substep of kEdgesSubstep
/// (free nodes: x += v h) takes from passing each other on one side to the next state `kind`
/// names; the scenario's nodes are 4 k to 4 k + 3 (k the scenario's index: edge a, then b).
enum class EdgesInOneSubstep : std::uint32_t {
  kThrough,         ///< edge a from 4 mm above b to 2 mm below it: within the hold depth
  kThroughDeep,     ///< a to 26 mm below b: deeper than the hold depth (a tunnel)
  kTurnedParallel,  ///< a stays 4 mm above b, its direction turned through b's (+20 to -20 deg)
};
inline constexpr float kEdgesSubstep = 1e-3f;

/// The three scenarios of EdgesInOneSubstep, 1 m apart, in one world: b along y in z = 0 and
/// at rest, a 4 mm above it, its side where the window starts set as the world sets it
/// (response::edge_edge_start_side), its velocities what carries it to the named state.
inline RandomContacts edges_in_one_substep() {
  constexpr float kThickness = 0.01f;
  std::vector<glm::vec4> x, v;
  std::vector<std::uint32_t> body;
  response::FrameConstraints c;
  const auto along = [](float degrees) {
    const float r = glm::radians(degrees);
    return glm::vec3(std::cos(r), std::sin(r), 0.0f);
  };
  for (std::uint32_t k = 0; k < 3u; ++k) {
    const glm::vec3 origin(static_cast<float>(k), 0.0f, 0.0f);
    const auto kind = static_cast<EdgesInOneSubstep>(k);
    const glm::vec3 a_dir = along(kind == EdgesInOneSubstep::kTurnedParallel ? 110.0f : 45.0f);
    const glm::vec3 lift(0.0f, 0.0f, 0.004f);
    const glm::vec3 a0 = origin + lift - 0.1f * a_dir, a1 = origin + lift + 0.1f * a_dir;
    glm::vec3 move0(0.0f), move1(0.0f);  // each end's move in the substep
    if (kind == EdgesInOneSubstep::kThrough) move0 = move1 = glm::vec3(0.0f, 0.0f, -0.006f);
    if (kind == EdgesInOneSubstep::kThroughDeep) move0 = move1 = glm::vec3(0.0f, 0.0f, -0.03f);
    if (kind == EdgesInOneSubstep::kTurnedParallel) {
      // From 110 to 70 degrees, through b's direction (90), the ends on the circle's chord.
      move0 = -0.1f * (along(70.0f) - a_dir);
      move1 = 0.1f * (along(70.0f) - a_dir);
    }
    const glm::vec3 b0 = origin + glm::vec3(0.0f, -0.1f, 0.0f);
    const glm::vec3 b1 = origin + glm::vec3(0.0f, 0.1f, 0.0f);
    const glm::vec3 corners[4] = {a0, a1, b0, b1};
    const glm::vec3 moves[4] = {move0, move1, glm::vec3(0.0f), glm::vec3(0.0f)};
    for (int i = 0; i < 4; ++i) {
      x.emplace_back(corners[i], 1.0f);
      v.emplace_back(moves[i] / kEdgesSubstep, 0.0f);
      body.push_back(0u);
    }
    gpu::ContactPair pair{};
    for (std::uint32_t i = 0; i < 4u; ++i)
      pair.nodes[i] = 4u * k + i;
    pair.kind = gpu::kContactEdgeEdge;
    pair.thickness = kThickness;
    pair.hold_depth = kThickness;
    pair.gap = -INFINITY;  // awake
    pair.converge = 1.0f;
    pair.side = response::edge_edge_start_side(corners);
    c.pairs.push_back(pair);
  }
  c.node_motion.assign(x.size(), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));  // reach 1 m: no stray
  c.window_start = window_start_of(x);
  return {free_nodes(std::move(x), std::move(v), std::move(body), 1), std::move(c)};
}

/// The volume constraints (gpu::kContactVolume) of every tetrahedron of `world`, each kept at
/// `floor` x its volume in `world`'s positions, its corners moved at most `step_limit` an
/// iteration.
inline std::vector<gpu::ContactPair> volume_constraints(const SimulationState& world, float floor,
                                                        float step_limit) {
  std::vector<gpu::ContactPair> out;
  for (const gpu::Tetra& t : world.tets) {
    gpu::ContactPair pair{};
    pair.nodes[0] = t.a;
    pair.nodes[1] = t.b;
    pair.nodes[2] = t.c;
    pair.nodes[3] = t.d;
    pair.kind = gpu::kContactVolume;
    pair.thickness = floor * t.rest_volume;
    pair.gap = -INFINITY;
    pair.step_limit = step_limit;
    pair.converge = 1.0f;  // as the world flags them
    out.push_back(pair);
  }
  return out;
}

/// `pairs` constraints of every contact kind on `nodes` nodes packed into a 5 cm cube (so that
/// most constraints are active and nodes are shared by many), with random velocities, about a
/// tenth of the nodes fixed, three bodies of different motion bounds; then `volumes` volume
/// constraints on random corners (either orientation, so that about half start inverted),
/// their floors and step limits drawn so that most act and some are limited, a third of them
/// thin (ContactPair::side).
inline RandomContacts random_contacts(std::uint32_t seed, std::uint32_t nodes, std::uint32_t pairs,
                                      std::uint32_t volumes = 0, bool local = false) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_int_distribution<std::uint32_t> node(0, nodes - 1);
  std::vector<glm::vec4> x, v;
  std::vector<std::uint32_t> body;
  for (std::uint32_t i = 0; i < nodes; ++i) {
    const float inverse_mass = unit(rng) < 0.1f ? 0.0f : 0.5f + 2.0f * unit(rng);
    x.emplace_back(0.05f * unit(rng), 0.05f * unit(rng), 0.05f * unit(rng), inverse_mass);
    v.emplace_back(2.0f * unit(rng) - 1.0f, 2.0f * unit(rng) - 1.0f, 2.0f * unit(rng) - 1.0f, 0.0f);
    body.push_back(i % 3u);
  }
  // Local: the nodes spread 0.5 m along x and numbered along it, each constraint's four among
  // 8 consecutive ones (a window's constraints join neighbours, which the sweeps' halves keep
  // together).
  if (local) {
    for (glm::vec4& p : x)
      p.x *= 10.0f;
    std::sort(x.begin(), x.end(), [](const glm::vec4& a, const glm::vec4& b) { return a.x < b.x; });
  }
  RandomContacts out{free_nodes(std::move(x), std::move(v), std::move(body), 3), {}};
  const auto four_different_nodes = [&](gpu::ContactPair& pair) {
    const std::uint32_t base = local ? node(rng) % (nodes - 8u) : 0u;
    for (int k = 0; k < 4; ++k) {
      std::uint32_t n = 0;
      do {
        n = local ? base + node(rng) % 8u : node(rng);
      } while (std::find(pair.nodes, pair.nodes + k, n) != pair.nodes + k);
      pair.nodes[k] = n;
    }
  };
  for (std::uint32_t p = 0; p < pairs; ++p) {
    gpu::ContactPair pair{};
    four_different_nodes(pair);
    pair.kind = p % 3u;
    // Most vertex-face constraints started in front of their faces, some behind.
    if (pair.kind == gpu::kContactVertexFace) pair.side = unit(rng) < 0.8f ? 1.0f : 0.0f;
    // Edge pairs know the side they start on (as the world sets it), so that those the
    // projections take through each other are taken back (contact_geometry).
    if (pair.kind == gpu::kContactEdgeEdge) {
      const glm::vec3 corners[4] = {glm::vec3(out.world.positions[pair.nodes[0]]),
                                    glm::vec3(out.world.positions[pair.nodes[1]]),
                                    glm::vec3(out.world.positions[pair.nodes[2]]),
                                    glm::vec3(out.world.positions[pair.nodes[3]])};
      pair.side = response::edge_edge_start_side(corners);
    }
    // Every other one holds deeper than its thickness (a self pair the rest rule made thinner).
    if (pair.kind != gpu::kContactUntangle && p % 2u == 0u) pair.hold_depth = 0.03f;
    // Contacts iterate while violated (contact_violated), as the world sets them between bodies
    // that do not start the frame intersecting.
    if (pair.kind != gpu::kContactUntangle) pair.converge = 1.0f;
    pair.thickness = 0.005f + 0.03f * unit(rng);
    out.constraints.pairs.push_back(pair);
  }
  for (std::uint32_t p = 0; p < volumes; ++p) {
    gpu::ContactPair pair{};
    four_different_nodes(pair);
    pair.kind = gpu::kContactVolume;
    pair.thickness = 4e-6f * unit(rng);  // m^3: random corners span up to about 2e-5
    pair.gap = -INFINITY;
    pair.step_limit = 0.002f + 0.02f * unit(rng);
    pair.converge = p % 2u == 0u ? 1.0f : 0.0f;  // some iterate while below half their floor
    pair.side = p % 3u == 0u ? 1.0f : 0.0f;      // some thin: their corners' guards watch them
    out.constraints.pairs.push_back(pair);
  }
  // Paths as well as reaches: the watched centre moves along them.
  out.constraints.node_motion = node_motion_of_bodies(
      {glm::vec4(0.5f, 0.0f, -0.25f, 0.2f), glm::vec4(0.0f, 0.0f, 0.0f, 0.01f),
       glm::vec4(-1.0f, 2.0f, 0.5f, 0.003f)},
      out.world.node_body);
  out.constraints.window_start = window_start_of(out.world.positions);
  return out;
}

}  // namespace deformcd::test
