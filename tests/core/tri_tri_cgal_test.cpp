// Exact oracle for tri_tri_intersect: CGAL's do_intersect on Triangle_3 with exact predicates,
// on ~250k random float pairs. Every disagreement must lie in the uncertain zone, measured in
// double precision on the same float coordinates (support/triangle_separation.h): a contact CGAL
// does not see must lie within what the tolerances can bridge of touching (the triangles' true
// distance), an intersection we miss within the tolerance of apart or in zone_measure's zone
// (support/tri_tri_zone.h). zone_measure alone takes nearly parallel, nearly coplanar pairs by
// the planes' distance or the 2D margin, however far apart they lie within the planes: that let
// false contacts between faces of a gently curved sheet 0.5 x their size apart through (fixed
// in 46d992c). Hence the nearly coplanar categories, built in a random frame (x, y in a plane,
// z along its normal): nearly parallel and apart within the plane, nearly parallel and
// overlapping, faces of a curved sheet, and nearly collinear edges a gap apart.

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "core/collision/tri_tri_intersection.h"
#include "support/tri_tri_zone.h"
#include "support/triangle_separation.h"

namespace deformcd::collision {
namespace {

using Kernel = test::CgalKernel;
using glm::dvec2;
using glm::dvec3;
using glm::vec3;
using test::kZone;
using test::to_cgal;
using test::Tri;
using test::zone_measure;
using Pair = std::array<Tri, 2>;
using Tri2 = std::array<dvec2, 3>;
using Tri3 = std::array<dvec3, 3>;  // in a frame's coordinates

// A random orthonormal frame at a random place and scale: nearly coplanar pairs are built in its
// coordinates and rounded to float world coordinates, so that no plane is axis-aligned and the
// rounding is generic. The origin stays within a few sizes of the pair (as callers must keep it).
struct Frame {
  dvec3 origin;
  dvec3 e1;
  dvec3 e2;
  dvec3 n;
  double scale = 1.0;

  [[nodiscard]] Tri world(const Tri3& t) const {
    Tri out;
    for (int i = 0; i < 3; ++i)
      out[i] = vec3(origin + scale * (t[i].x * e1 + t[i].y * e2 + t[i].z * n));
    return out;
  }
};

double longest_edge(const Tri2& t) {
  return std::sqrt(std::max({glm::dot(t[1] - t[0], t[1] - t[0]), glm::dot(t[2] - t[1], t[2] - t[1]),
                             glm::dot(t[0] - t[2], t[0] - t[2])}));
}

double cross2(const dvec2& a, const dvec2& b) {
  return a.x * b.y - a.y * b.x;
}

// The 2D point x, at height 0, rotated by `angle` about the line through c along the unit
// `axis`, then lifted by h.
dvec3 tilt(const dvec2& x, const dvec2& c, const dvec2& axis, double angle, double h) {
  const dvec2 across_axis(-axis.y, axis.x);
  const double along = glm::dot(x - c, axis);
  const double across = glm::dot(x - c, across_axis);
  const dvec2 in_plane = c + along * axis + across * std::cos(angle) * across_axis;
  return {in_plane, across * std::sin(angle) + h};
}

class PairGenerator {
 public:
  explicit PairGenerator(unsigned seed) : rng_(seed) {}

  // A random pair in a unit box: about half of them intersect.
  Pair general() { return {triangle(), triangle()}; }

  // q's vertex k at a point of p's plane (inside or near p) moved off the plane by a distance
  // of 1e-7..1e-3 relative to the pair's size, to either side; q's other vertices on one side.
  Pair near_touching() {
    const Tri p = triangle();
    const dvec3 a(p[0]);
    const dvec3 n = glm::normalize(glm::cross(dvec3(p[1]) - a, dvec3(p[2]) - a));
    const double u = uniform(-0.2, 1.0);
    const double v = uniform(-0.2, 1.0 - u);
    const dvec3 on_plane = a + u * (dvec3(p[1]) - a) + v * (dvec3(p[2]) - a);
    const double size = 2.0;
    const double rel = std::pow(10.0, uniform(-7.0, -3.0));
    Tri q;
    q[0] = vec3(on_plane + n * (sign() * rel * size));
    for (int i = 1; i < 3; ++i) {
      const dvec3 x = on_plane + dvec3(point());
      const double h = std::abs(glm::dot(x - on_plane, n)) + 0.1;
      q[i] = vec3(x - n * glm::dot(x - on_plane, n) + n * (sign() * h));
    }
    return {p, q};
  }

  // Both in an exactly representable plane: z = 0 or y = x.
  Pair coplanar() {
    Pair pair{triangle(), triangle()};
    test::flatten_to_exact_plane(pair[0], pair[1], coin_(rng_));
    return pair;
  }

  // p a sliver: height 1e-5..1e-2 of its length.
  Pair sliver() {
    const vec3 a = point();
    const vec3 b = point();
    const vec3 off = glm::normalize(glm::cross(b - a, point()));
    const auto h = static_cast<float>(std::pow(10.0, uniform(-5.0, -2.0)));
    const auto t = static_cast<float>(uniform(0.0, 1.0));
    const Tri p{a, b, a + (b - a) * t + off * (h * glm::length(b - a))};
    return {p, triangle()};
  }

  // Nearly parallel (1e-7 .. 1e-2 rad) and apart within the plane: q beyond a line that p stays
  // behind, 1e-6 .. 0.5 x p's size from p's farthest vertex, tilted about a random line (half the
  // time through p) and lifted by 0 .. 3e-5 x size; a third of them with a vertex of q snapped
  // onto p's plane, where it may lie far from the planes' line.
  Pair parallel_apart() {
    const Tri2 p = triangle_2d();
    const double size = longest_edge(p);
    const dvec2 w = direction();
    const dvec2 along_gap(-w.y, w.x);
    const dvec2* farthest = &p[0];
    for (const dvec2& x : p)
      if (glm::dot(x, w) > glm::dot(*farthest, w)) farthest = &x;
    const double gap = size * std::pow(10.0, uniform(-6.0, std::log10(0.5)));
    Tri2 q;
    q[0] = *farthest + gap * w + uniform(-0.3, 0.3) * size * along_gap;
    for (int i = 1; i < 3; ++i) {  // beyond q[0] along w; a quarter of the edges along the line
      const double angle = coin_(rng_) && coin_(rng_) ? sign() * 1.5707963 : uniform(-1.5, 1.5);
      const dvec2 e = std::cos(angle) * w + std::sin(angle) * along_gap;
      q[i] = q[0] + uniform(0.3, 1.0) * size * e;
    }
    const dvec2 c = coin_(rng_) ? point_of(p) : *farthest + uniform(-0.5, 1.0) * size * w;
    const double lift = coin_(rng_) && coin_(rng_) ? 0.0 : sign() * uniform(0.0, 3e-5) * size;
    return lifted_pair(p, q, c, lift);
  }

  // Nearly parallel and overlapping within the plane (q random in the same box, or half the
  // time just inside or outside an edge of p, 1e-7 .. 1e-2 x size), tilted about a line
  // through p or q and lifted by 1e-7 .. 1e-4 x size: crossings and near misses.
  Pair parallel_overlapping() {
    const Tri2 p = triangle_2d();
    const double size = longest_edge(p);
    Tri2 q = triangle_2d();
    if (coin_(rng_)) {  // q outward of p's edge k, its vertex 0 near the edge
      const int k = std::uniform_int_distribution<int>(0, 2)(rng_);
      const dvec2 a = p[k];
      const dvec2 b = p[(k + 1) % 3];
      dvec2 out = glm::normalize(dvec2(b.y - a.y, a.x - b.x));
      if (glm::dot(out, p[(k + 2) % 3] - a) > 0.0) out = -out;
      q[0] = a + uniform(0.0, 1.0) * (b - a) + sign() * std::pow(10.0, uniform(-7.0, -2.0)) * out;
      for (int i = 1; i < 3; ++i)
        q[i] = q[0] + uniform(0.2, 1.0) * size *
                          glm::normalize(out + uniform(-2.0, 2.0) * glm::normalize(b - a));
    }
    const dvec2 c = coin_(rng_) ? point_of(p) : point_of(q);
    const double lift =
        coin_(rng_) && coin_(rng_) ? 0.0 : sign() * std::pow(10.0, uniform(-7.0, -4.0)) * size;
    return lifted_pair(p, q, c, lift);
  }

  // Two faces sharing no node of a gently curved sheet, in neighbouring cells: a 6 x 6 grid, its
  // nodes jittered within the plane, on a height field z = (a x^2 + 2 b x y + c y^2) / 2 with
  // curvatures 1e-7 .. 1e-4 per cell (3/4 of them: vertices within the plane tolerance of a
  // neighbour's plane, and others not) or 1e-4 .. 1e-2, plus most of the time noise of
  // 1e-7 .. 1e-5 x the cell (either side of the plane). The sheet never intersects itself: CGAL
  // always says apart, while the faces lie less than a cell apart within the plane (the case of
  // 46d992c, first seen on the folding plate).
  Pair sheet() {
    constexpr int kCells = 6;
    constexpr int kNodes = kCells + 1;
    const double jitter = coin_(rng_) ? 0.0 : uniform(0.0, 0.3);
    const double curvature =
        std::pow(10.0, coin_(rng_) || coin_(rng_) ? uniform(-7.0, -4.0) : uniform(-4.0, -2.0));
    const double a = sign() * curvature * uniform(0.0, 1.0);
    const double b = sign() * curvature * uniform(0.0, 1.0);
    const double c = sign() * curvature * uniform(0.0, 1.0);
    const double noise =
        coin_(rng_) && coin_(rng_) && coin_(rng_) ? 0.0 : std::pow(10.0, uniform(-7.0, -5.0));
    std::vector<dvec3> nodes;
    for (int j = 0; j < kNodes; ++j) {
      for (int i = 0; i < kNodes; ++i) {
        const double x = i - 0.5 * kCells + uniform(-jitter, jitter);
        const double y = j - 0.5 * kCells + uniform(-jitter, jitter);
        const double z = 0.5 * (a * x * x + 2.0 * b * x * y + c * y * y);
        nodes.emplace_back(x, y, z + noise * uniform(-1.0, 1.0));
      }
    }
    // Face `half` of cell (i, j): two per cell, split along one diagonal or the other at random.
    const bool other_diagonal = coin_(rng_);
    auto face = [&](int i, int j, int half) {
      const int n00 = j * kNodes + i;
      const int n10 = n00 + 1;
      const int n01 = n00 + kNodes;
      const int n11 = n01 + 1;
      if (other_diagonal)
        return half == 0 ? std::array<int, 3>{n00, n10, n11} : std::array<int, 3>{n00, n11, n01};
      return half == 0 ? std::array<int, 3>{n00, n10, n01} : std::array<int, 3>{n10, n11, n01};
    };
    std::uniform_int_distribution<int> cell(0, kCells - 1);
    std::uniform_int_distribution<int> near(-1, 1);
    for (;;) {
      const int i = cell(rng_);
      const int j = cell(rng_);
      const int i2 = i + near(rng_);
      const int j2 = j + near(rng_);
      if (i2 < 0 || i2 >= kCells || j2 < 0 || j2 >= kCells) continue;
      const std::array<int, 3> f = face(i, j, coin_(rng_) ? 1 : 0);
      const std::array<int, 3> g = face(i2, j2, coin_(rng_) ? 1 : 0);
      bool shared = false;
      for (int x : f)
        shared = shared || std::find(g.begin(), g.end(), x) != g.end();
      if (shared) continue;
      const Frame fr = frame();
      return {fr.world({nodes[f[0]], nodes[f[1]], nodes[f[2]]}),
              fr.world({nodes[g[0]], nodes[g[1]], nodes[g[2]]})};
    }
  }

  // Apart within one plane along nearly collinear edges: p's edge from (0, 0) back to
  // (-l, 0), q's from (g, 0) on at 1e-7 .. 1e-3 rad to it, g = 1e-6 .. 0.5 x size, the third
  // vertices on either side within the edges' extent (so the triangles lie g apart). Half of
  // them exactly in one plane, half tilted (up to 1e-4 rad) and lifted as lifted_pair does.
  // A segment test that takes an end within the orientation tolerance of the other's line for
  // a point of the other segment, without checking that it lies within the other's extent,
  // reports such edges as meeting.
  Pair collinear_edges() {
    const double l1 = uniform(0.3, 1.0);
    const double l2 = uniform(0.3, 1.0);
    const double gap = std::pow(10.0, uniform(-6.0, std::log10(0.5)));
    const double psi = sign() * std::pow(10.0, uniform(-7.0, -3.0));
    const Tri2 p{dvec2(0.0, 0.0), dvec2(-l1, 0.0),
                 dvec2(-uniform(0.0, l1), sign() * uniform(0.2, 1.0))};
    const dvec2 d(gap, 0.0);
    const dvec2 c = d + l2 * dvec2(std::cos(psi), std::sin(psi));
    const Tri2 q{c, d, dvec2(gap + uniform(0.0, l2), sign() * uniform(0.2, 1.0))};
    if (coin_(rng_)) return lifted_pair(p, q, point_of(p), 0.0, -4.0);
    const Frame f = frame();
    Tri3 p3;
    Tri3 q3;
    for (int i = 0; i < 3; ++i) {
      p3[i] = dvec3(p[i], 0.0);
      q3[i] = dvec3(q[i], 0.0);
    }
    return {f.world(p3), f.world(q3)};
  }

 private:
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  double sign() { return coin_(rng_) ? 1.0 : -1.0; }
  vec3 point() { return vec3(unit_(rng_), unit_(rng_), unit_(rng_)); }
  Tri triangle() { return {point(), point(), point()}; }

  dvec2 direction() {
    const double angle = uniform(0.0, 6.283185307179586);
    return {std::cos(angle), std::sin(angle)};
  }

  // A frame at a random orientation, scale 1e-2 .. 1e2, origin within 3 scales.
  Frame frame() {
    Frame f;
    f.scale = std::pow(10.0, uniform(-2.0, 2.0));
    f.origin = dvec3(point()) * (3.0 * f.scale);
    f.n = glm::normalize(dvec3(point()) + dvec3(0.0, 0.0, 1e-3));
    f.e1 = glm::normalize(glm::cross(f.n, dvec3(point()) + dvec3(1e-3, 0.0, 0.0)));
    f.e2 = glm::cross(f.n, f.e1);
    return f;
  }

  // A 2D triangle in [-0.5, 0.5]^2, not a sliver: area >= 0.1 x longest edge^2.
  Tri2 triangle_2d() {
    for (;;) {
      const Tri2 t{dvec2(uniform(-0.5, 0.5), uniform(-0.5, 0.5)),
                   dvec2(uniform(-0.5, 0.5), uniform(-0.5, 0.5)),
                   dvec2(uniform(-0.5, 0.5), uniform(-0.5, 0.5))};
      const double l = longest_edge(t);
      if (0.5 * std::abs(cross2(t[1] - t[0], t[2] - t[0])) >= 0.1 * l * l) return t;
    }
  }

  dvec2 point_of(const Tri2& t) {
    const double u = uniform(0.0, 1.0);
    const double v = uniform(0.0, 1.0 - u);
    return t[0] + u * (t[1] - t[0]) + v * (t[2] - t[0]);
  }

  // p at height 0, q tilted by 1e-7 .. 10^max_tilt rad about a random line through c and lifted
  // by `lift`; a third of the time instead shifted along the normal so that one of its vertices
  // lies within 0.9 x the plane tolerance of p's plane (snapped by the algorithm).
  Pair lifted_pair(const Tri2& p, const Tri2& q, const dvec2& c, double lift,
                   double max_tilt = -2.0) {
    const double size = std::max(longest_edge(p), longest_edge(q));
    const dvec2 axis = direction();
    const double angle = sign() * std::pow(10.0, uniform(-7.0, max_tilt));
    Tri3 p3;
    Tri3 q3;
    for (int i = 0; i < 3; ++i) {
      p3[i] = dvec3(p[i], 0.0);
      q3[i] = tilt(q[i], c, axis, angle, lift);
    }
    if (std::uniform_int_distribution<int>(0, 2)(rng_) == 0) {
      const dvec3 snapped = q3[std::uniform_int_distribution<int>(0, 2)(rng_)];
      const double shift = uniform(-0.9, 0.9) * double(kTriTriTolerance) * size - snapped.z;
      for (dvec3& x : q3)
        x.z += shift;
    }
    const Frame f = frame();
    return {f.world(p3), f.world(q3)};
  }

  std::mt19937 rng_;
  std::uniform_real_distribution<float> unit_{-1.0f, 1.0f};
  std::bernoulli_distribution coin_{0.5};
};

struct Counts {
  int total = 0;
  int exact = 0;  // intersecting per CGAL
  int ours = 0;   // intersecting per tri_tri_intersect
  int agree = 0;
  int in_zone = 0;
  int outside_zone = 0;
  // The largest measure (support/triangle_separation.h) of a disagreement in the zone: a contact
  // CGAL does not see, an intersection we miss.
  double worst_separation = 0.0;
  double worst_apart = 0.0;
};

void compare(const Pair& pair, Counts& counts) {
  const Kernel::Triangle_3 cp = to_cgal(pair[0]);
  const Kernel::Triangle_3 cq = to_cgal(pair[1]);
  if (cp.is_degenerate() || cq.is_degenerate()) return;  // outside CGAL's precondition
  ++counts.total;
  const bool exact = CGAL::do_intersect(cp, cq);
  const bool ours = tri_tri_intersect(pair[0].data(), pair[1].data()).intersect;
  counts.exact += exact ? 1 : 0;
  counts.ours += ours ? 1 : 0;
  if (exact == ours) {
    ++counts.agree;
    return;
  }
  const double measure = test::disagreement_measure(pair[0], pair[1], exact);
  if (measure < kZone) {
    ++counts.in_zone;
    double& worst = exact ? counts.worst_apart : counts.worst_separation;
    worst = std::max(worst, measure);
  } else if (++counts.outside_zone <= 5) {
    ADD_FAILURE() << "outside the uncertain zone: CGAL " << exact << ", ours " << ours
                  << ", zone measure " << zone_measure(pair[0], pair[1]) << ", separation measure "
                  << test::separation_measure(pair[0], pair[1]) << ", apart measure "
                  << test::apart_measure(pair[0], pair[1]) << " (zone " << kZone << "), pair"
                  << test::describe_pair(pair[0], pair[1]);
  }
}

struct Category {
  std::string name;
  Pair (PairGenerator::*make)();
  int pairs;
  bool both_answers;  // CGAL says intersecting for 5 .. 95 % of them
  Counts counts;
};

// Compares `pairs` pairs of each category, prints and records the counts; returns the number of
// disagreements outside the zone.
int run_categories(PairGenerator& gen, std::vector<Category> categories) {
  for (Category& c : categories)
    for (int n = 0; n < c.pairs; ++n)
      compare((gen.*c.make)(), c.counts);
  int outside_zone = 0;
  for (const Category& c : categories) {
    const Counts& k = c.counts;
    std::cout << c.name << ": total " << k.total << ", intersecting CGAL " << k.exact << ", ours "
              << k.ours << "; agree " << k.agree << ", disagree in zone " << k.in_zone
              << " (largest measure: contacts CGAL does not see " << k.worst_separation
              << ", intersections missed " << k.worst_apart << "), outside zone " << k.outside_zone
              << "\n";
    ::testing::Test::RecordProperty(c.name + "_disagree_in_zone", k.in_zone);
    ::testing::Test::RecordProperty(c.name + "_disagree_outside_zone", k.outside_zone);
    outside_zone += k.outside_zone;
    EXPECT_GT(k.total, c.pairs * 9 / 10) << c.name;
    if (c.both_answers) {  // so that neither answer is tested vacuously
      EXPECT_GT(k.exact, k.total / 20) << c.name;
      EXPECT_LT(k.exact, k.total - k.total / 20) << c.name;
    }
  }
  return outside_zone;
}

TEST(TriTriAgainstCgal, DisagreesOnlyInTheUncertainZone) {
  PairGenerator gen(20260101u);
  const int outside_zone = run_categories(
      gen, {{"general", &PairGenerator::general, 25000, true, {}},
            {"near_touching", &PairGenerator::near_touching, 25000, true, {}},
            {"coplanar", &PairGenerator::coplanar, 25000, true, {}},
            {"sliver", &PairGenerator::sliver, 25000, true, {}},
            {"parallel_apart", &PairGenerator::parallel_apart, 40000, false, {}},
            {"parallel_overlapping", &PairGenerator::parallel_overlapping, 40000, true, {}},
            {"sheet", &PairGenerator::sheet, 40000, false, {}}});
  EXPECT_EQ(outside_zone, 0);
}

// Disabled until segments_meet_2d (core/collision/tri_tri_primitives.h, and its GLSL mirror)
// checks that an end within the tolerance of the other segment's line lies within that
// segment's extent: now 880 of these 40000 pairs are reported meeting while up to ~0.2 x their
// size apart (e.g. coplanar triangles {0,0,0} {-1,0,0} {-0.5,1,0} and {1.6,1e-4,0} {0.6,0,0}
// {0,2,0}, 0.57 apart). Enable with that fix.
TEST(TriTriAgainstCgal, NearlyCollinearEdgesApartWithinThePlane) {
  PairGenerator gen(20260102u);
  const int outside_zone =
      run_categories(gen, {{"collinear_edges", &PairGenerator::collinear_edges, 40000, false, {}}});
  EXPECT_EQ(outside_zone, 0);
}

// Issue 14, "no missed pair": a pair that CGAL's exact test (Epeck, on the float coordinates)
// says intersects must never be reported apart. "Apart" is an answer given only beyond the
// tolerance; inside it the pair is decided as touching, so false positives in the zone are
// allowed (counted, and each must lie within the zone of touching) but false negatives are not.
// A pair with a near-degenerate triangle (|n| <= kTriTriDegenerateTolerance L^2, a third of the
// slivers) intersects nothing by the public contract (detector.h, README): counted apart.
// 1,000,000 pairs by default (~2 s in release); DEFORMCD_NO_MISS_PAIRS=<n> and
// DEFORMCD_NO_MISS_SEED=<seed> run other amounts and seeds.
struct MissCounts {
  std::int64_t total = 0;
  std::int64_t exact = 0;
  std::int64_t false_negatives = 0;
  std::int64_t false_positives = 0;          // all of them in the zone, else a failure
  std::int64_t false_positives_outside = 0;  // separation_measure >= kZone
  std::int64_t degenerate = 0;               // a triangle below kTriTriDegenerateTolerance
  std::int64_t degenerate_misses = 0;        // of those, intersecting per CGAL (the contract)
  std::int64_t geometry_differs = 0;         // tri_tri_intersect from TriangleGeometry differs
};

bool same_bits(const vec3& x, const vec3& y) {
  return std::memcmp(&x, &y, sizeof(vec3)) == 0;
}

// The CPU broad phases' entry (each triangle's geometry made once) against the plain one.
bool same_result_from_geometry(const Tri& p, const Tri& q) {
  const TriTriResult plain = tri_tri_intersect(p.data(), q.data());
  const TriTriResult prepared =
      tri_tri_intersect(triangle_geometry(p.data()), triangle_geometry(q.data()));
  return plain.intersect == prepared.intersect && plain.coplanar == prepared.coplanar &&
         same_bits(plain.segment[0], prepared.segment[0]) &&
         same_bits(plain.segment[1], prepared.segment[1]);
}

bool near_degenerate(const Tri& t) {
  const vec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
  float l2 = 0.0f;
  for (int i = 0; i < 3; ++i) {
    const vec3 e = t[(i + 1) % 3] - t[i];
    l2 = std::max(l2, glm::dot(e, e));
  }
  return !(glm::length(n) > kTriTriDegenerateTolerance * l2);
}

void compare_no_miss(const Pair& pair, const std::string& name, MissCounts& k) {
  using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
  auto exact_triangle = [](const Tri& t) {
    auto point = [](const vec3& x) { return Exact::Point_3(x.x, x.y, x.z); };
    return Exact::Triangle_3(point(t[0]), point(t[1]), point(t[2]));
  };
  const Exact::Triangle_3 cp = exact_triangle(pair[0]);
  const Exact::Triangle_3 cq = exact_triangle(pair[1]);
  if (cp.is_degenerate() || cq.is_degenerate()) return;  // outside CGAL's precondition
  ++k.total;
  const bool degenerate = near_degenerate(pair[0]) || near_degenerate(pair[1]);
  k.degenerate += degenerate ? 1 : 0;
  const bool exact = CGAL::do_intersect(cp, cq);
  const bool ours = tri_tri_intersect(pair[0].data(), pair[1].data()).intersect;
  if (!same_result_from_geometry(pair[0], pair[1]) && ++k.geometry_differs <= 5) {
    ADD_FAILURE() << name << ": the result from TriangleGeometry differs, pair"
                  << test::describe_pair(pair[0], pair[1]);
  }
  k.exact += exact ? 1 : 0;
  if (exact && !ours && degenerate) {
    ++k.degenerate_misses;
  } else if (exact && !ours) {
    if (++k.false_negatives <= 5) {
      ADD_FAILURE() << name << ": CGAL intersects, reported apart"
                    << ", zone measure " << zone_measure(pair[0], pair[1]) << ", apart measure "
                    << test::apart_measure(pair[0], pair[1]) << ", pair"
                    << test::describe_pair(pair[0], pair[1]);
    }
  } else if (!exact && ours) {
    ++k.false_positives;
    if (test::separation_measure(pair[0], pair[1]) >= kZone && ++k.false_positives_outside <= 5) {
      ADD_FAILURE() << name << ": a contact outside the zone, separation measure "
                    << test::separation_measure(pair[0], pair[1]) << ", pair"
                    << test::describe_pair(pair[0], pair[1]);
    }
  }
}

TEST(TriTriAgainstCgal, NoMissedPair) {
  std::int64_t total = 1000000;
  if (const char* env = std::getenv("DEFORMCD_NO_MISS_PAIRS")) total = std::atoll(env);
  struct Share {
    std::string name;
    Pair (PairGenerator::*make)();
    double fraction;
  };
  const std::vector<Share> shares = {
      {"near_touching", &PairGenerator::near_touching, 0.25},
      {"coplanar", &PairGenerator::coplanar, 0.20},
      {"sliver", &PairGenerator::sliver, 0.25},
      {"nearly_coplanar", &PairGenerator::parallel_overlapping, 0.20},
      {"nearly_coplanar_apart", &PairGenerator::parallel_apart, 0.05},
      {"collinear_edges", &PairGenerator::collinear_edges, 0.05}};
  unsigned seed = 20260114u;
  if (const char* env = std::getenv("DEFORMCD_NO_MISS_SEED")) seed = unsigned(std::atoll(env));
  PairGenerator gen(seed);
  const auto start = std::chrono::steady_clock::now();
  MissCounts all;
  for (const Share& s : shares) {
    MissCounts k;
    const auto n = static_cast<std::int64_t>(s.fraction * double(total));
    for (std::int64_t i = 0; i < n; ++i)
      compare_no_miss((gen.*s.make)(), s.name, k);
    std::cout << s.name << ": total " << k.total << ", intersecting (CGAL) " << k.exact
              << ", false negatives " << k.false_negatives << ", false positives in zone "
              << k.false_positives - k.false_positives_outside << ", outside zone "
              << k.false_positives_outside << "; near-degenerate pairs " << k.degenerate
              << ", of which intersecting per CGAL (apart by contract) " << k.degenerate_misses
              << "\n";
    ::testing::Test::RecordProperty(s.name + "_false_negatives", std::to_string(k.false_negatives));
    ::testing::Test::RecordProperty(s.name + "_false_positives", std::to_string(k.false_positives));
    EXPECT_GT(k.total, n * 9 / 10) << s.name;
    all.total += k.total;
    all.false_negatives += k.false_negatives;
    all.false_positives += k.false_positives;
    all.false_positives_outside += k.false_positives_outside;
    all.geometry_differs += k.geometry_differs;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "all: " << all.total << " pairs in " << seconds << " s, false negatives "
            << all.false_negatives << ", false positives " << all.false_positives
            << " (outside the zone " << all.false_positives_outside << ")\n";
  EXPECT_EQ(all.false_negatives, 0);
  EXPECT_EQ(all.false_positives_outside, 0);
  EXPECT_EQ(all.geometry_differs, 0);
}

}  // namespace
}  // namespace deformcd::collision
