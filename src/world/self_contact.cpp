#include "world/self_contact.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

namespace deformcd {

namespace {

// The rotation of the polar decomposition of A (the rotation nearest to it), improved from q
// (Mueller, Bender, Chentanez and Macklin 2016, "A robust method to extract the rotational part
// of deformations"): each step turns q about the axis that brings its columns towards A's.
// Deterministic, and robust where A is degenerate (a flat or inverted fit keeps the last q).
glm::dquat nearest_rotation(const glm::dmat3& a, glm::dquat q) {
  for (int step = 0; step < 20; ++step) {
    const glm::dmat3 r = glm::mat3_cast(q);
    const glm::dvec3 torque =
        glm::cross(r[0], a[0]) + glm::cross(r[1], a[1]) + glm::cross(r[2], a[2]);
    const double alignment =
        std::abs(glm::dot(r[0], a[0]) + glm::dot(r[1], a[1]) + glm::dot(r[2], a[2])) + 1e-9;
    const glm::dvec3 omega = torque / alignment;
    const double angle = glm::length(omega);
    if (!(angle > 1e-9)) break;  // NaN too: keep q
    q = glm::normalize(glm::angleAxis(angle, omega / angle) * q);
  }
  return q;
}

// A node's position (glm::vec3, or glm::vec4's xyz) in double.
template <class X>
glm::dvec3 at(const X& x) {
  return glm::dvec3(glm::vec3(x));
}

}  // namespace

SelfContact::SelfContact(const std::vector<gpu::ObjectInfo>& objects,
                         const std::vector<std::uint8_t>& on_surface, std::vector<float> thickness)
    : objects_(objects),
      thickness_(std::move(thickness)),
      surface_(objects.size()),
      reference_(objects.size()),
      rotation_(objects.size(), glm::dquat(1.0, 0.0, 0.0, 0.0)),
      pairs_(objects.size()) {
  for (std::size_t b = 0; b < objects_.size(); ++b) {
    const gpu::ObjectInfo& o = objects_[b];
    for (std::uint32_t i = o.node_offset; i < o.node_offset + o.node_count; ++i)
      if (on_surface[i] != 0u) surface_[b].push_back(i);
  }
}

template <class X>
double SelfContact::drift(std::uint32_t body, const X& x) {
  // In double, summed in surface order: the centroids, then the rotation of the covariance's
  // polar decomposition, which takes the reference offsets to the positions' (warm-started).
  const std::vector<std::uint32_t>& surface = surface_[body];
  const std::vector<glm::vec3>& p = reference_[body];
  if (surface.empty()) return 0.0;
  glm::dvec3 x_sum(0.0), p_sum(0.0);
  for (std::size_t k = 0; k < surface.size(); ++k) {
    x_sum += at(x[surface[k]]);
    p_sum += glm::dvec3(p[k]);
  }
  const auto count = static_cast<double>(surface.size());
  const glm::dvec3 x_mid = x_sum / count, p_mid = p_sum / count;
  glm::dmat3 covariance(0.0);
  for (std::size_t k = 0; k < surface.size(); ++k)
    covariance += glm::outerProduct(at(x[surface[k]]) - x_mid, glm::dvec3(p[k]) - p_mid);
  rotation_[body] = nearest_rotation(covariance, rotation_[body]);
  const glm::dmat3 back = glm::transpose(glm::mat3_cast(rotation_[body]));
  double most = 0.0;
  for (std::size_t k = 0; k < surface.size(); ++k) {
    const double d = glm::length(back * (at(x[surface[k]]) - x_mid) + p_mid - glm::dvec3(p[k]));
    if (!(d <= most)) most = d;  // NaN stays (and fails every bound)
  }
  return most;
}

template <class X>
double SelfContact::deformation(std::uint32_t body, const X& x,
                                std::span<const glm::vec4> node_motion, float window) const {
  // The best rigid fit to the surface's velocities: the mean velocity, and the angular velocity
  // for which inertia x omega = angular momentum (unit masses). A turn by `turn` radians leaves
  // the straight path by at most turn^2 of the radius (for turn <= 1/2).
  const std::vector<std::uint32_t>& surface = surface_[body];
  if (surface.empty()) return 0.0;
  glm::dvec3 x_sum(0.0), v_sum(0.0);
  for (const std::uint32_t i : surface) {
    x_sum += at(x[i]);
    v_sum += at(node_motion[i]);
  }
  const auto count = static_cast<double>(surface.size());
  const glm::dvec3 x_mid = x_sum / count, v_mid = v_sum / count;
  glm::dmat3 inertia(0.0);
  glm::dvec3 momentum(0.0);
  for (const std::uint32_t i : surface) {
    const glm::dvec3 r = at(x[i]) - x_mid;
    inertia += glm::dmat3(glm::dot(r, r)) - glm::outerProduct(r, r);
    momentum += glm::cross(r, at(node_motion[i]) - v_mid);
  }
  const double det = glm::determinant(inertia);
  const double scale = inertia[0][0] + inertia[1][1] + inertia[2][2];
  const glm::dvec3 omega = std::abs(det) > 1e-12 * scale * scale * scale
                               ? glm::inverse(inertia) * momentum
                               : glm::dvec3(0.0);
  const double turn = glm::length(omega) * static_cast<double>(window);
  if (!(turn <= 0.5)) return INFINITY;  // NaN too
  double most = 0.0;
  for (const std::uint32_t i : surface) {
    const glm::dvec3 r = at(x[i]) - x_mid;
    const double d = glm::length(at(node_motion[i]) - v_mid - glm::cross(omega, r)) *
                         static_cast<double>(window) +
                     turn * turn * glm::length(r);
    if (!(d <= most)) most = d;
  }
  return most;
}

SelfContact::Plan SelfContact::plan(const std::vector<glm::vec3>& x,
                                    const std::vector<glm::vec4>& node_motion, float window,
                                    const std::vector<std::uint8_t>& movable) {
  Plan plan{std::vector<std::uint8_t>(objects_.size(), 0u),
            std::vector<std::uint8_t>(objects_.size(), 0u)};
  for (std::uint32_t b = 0; b < objects_.size(); ++b) {
    if (movable[b] == 0u) continue;
    const double margin = kMargin * thickness_[b];
    const double deforms = deformation(b, x, node_motion, window);
    if (has_references(b) && drift(b, x) + deforms <= margin) {
      plan.kept[b] = 1u;
    } else if (deforms <= 0.5 * margin) {
      plan.search[b] = 1u;
    }
  }
  return plan;
}

std::vector<float> SelfContact::search_reach() const {
  std::vector<float> reach(
      objects_.empty() ? 0u : objects_.back().node_offset + objects_.back().node_count);
  for (std::uint32_t b = 0; b < objects_.size(); ++b) {
    const gpu::ObjectInfo& o = objects_[b];
    std::fill(reach.begin() + o.node_offset, reach.begin() + o.node_offset + o.node_count,
              (0.5f + kMargin) * thickness_[b]);
  }
  return reach;
}

void SelfContact::take(const std::vector<ProximityPair>& found, const std::vector<glm::vec3>& x,
                       const std::vector<std::uint8_t>& searched) {
  for (std::uint32_t b = 0; b < objects_.size(); ++b) {
    if (searched[b] == 0u) continue;
    reference_[b].clear();
    for (const std::uint32_t i : surface_[b])
      reference_[b].push_back(x[i]);
    rotation_[b] = glm::dquat(1.0, 0.0, 0.0, 0.0);
    pairs_[b].clear();
  }
  for (const ProximityPair& p : found)
    if (p.mesh_a == p.mesh_b && searched[p.mesh_a] != 0u) pairs_[p.mesh_a].push_back(p);
}

bool SelfContact::holds(std::uint32_t body, std::span<const glm::vec4> x,
                        std::span<const glm::vec4> v, float h) {
  return has_references(body) &&
         drift(body, x) + deformation(body, x, v, h) <= kMargin * thickness_[body];
}

}  // namespace deformcd
