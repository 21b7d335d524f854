#include "world/body_sleep.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include <glm/vec3.hpp>

#include "deformcd/error.h"

namespace deformcd {

BodySleep::BodySleep(const SleepSettings& settings, const std::vector<gpu::ObjectInfo>& objects,
                     std::vector<float> inverse_mass, const std::vector<float>& mean_edge,
                     const std::vector<std::uint8_t>& may_sleep, float dt)
    : settings_(settings),
      objects_(objects),
      inverse_mass_(std::move(inverse_mass)),
      may_sleep_(may_sleep),
      fixed_(objects.size(), 1u),
      asleep_(objects.size(), 0u),
      slept_with_(objects.size(), 0u),
      slow_time_(objects.size(), 0.0f),
      dt_(dt) {
  for (std::size_t b = 0; b < objects_.size(); ++b) {
    slow_speed_.push_back(settings_.speed * mean_edge[b]);
    const gpu::ObjectInfo& o = objects_[b];
    for (std::uint32_t i = o.node_offset; i < o.node_offset + o.node_count; ++i)
      if (inverse_mass_[i] > 0.0f) fixed_[b] = 0u;
  }
}

double BodySleep::rms_motion(std::size_t body, std::span<const glm::vec4> position) const {
  // In node order, in double: the same sum on every backend and thread count.
  const gpu::ObjectInfo& o = objects_[body];
  double mass = 0.0, weighted = 0.0;
  for (std::uint32_t i = o.node_offset; i < o.node_offset + o.node_count; ++i) {
    if (!(inverse_mass_[i] > 0.0f)) continue;
    const double m = 1.0 / static_cast<double>(inverse_mass_[i]);
    const glm::dvec3 d = glm::dvec3(glm::vec3(position[i])) - glm::dvec3(last_position_[i]);
    mass += m;
    weighted += m * (d.x * d.x + d.y * d.y + d.z * d.z);
  }
  return mass > 0.0 ? std::sqrt(weighted / mass) / static_cast<double>(dt_) : 0.0;
}

std::vector<std::uint32_t> BodySleep::end_frame(
    std::span<const glm::vec4> position,
    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& links,
    std::span<const std::uint8_t> inverted) {
  const std::size_t n = objects_.size();
  if (!inverted.empty() && inverted.size() != n)
    throw Error("BodySleep::end_frame: " + std::to_string(inverted.size()) +
                " inverted flags for " + std::to_string(n) + " bodies");
  const bool first_frame = last_position_.empty();
  for (std::size_t b = 0; b < n; ++b) {
    if (fixed_[b] != 0u) continue;
    const bool shaped = inverted.empty() || inverted[b] == 0u;
    const bool slow =
        asleep_[b] != 0u ||
        (!first_frame && shaped && rms_motion(b, position) < static_cast<double>(slow_speed_[b]));
    slow_time_[b] = slow ? slow_time_[b] + dt_ : 0.0f;
  }
  last_position_.resize(position.size());
  for (std::size_t i = 0; i < position.size(); ++i)
    last_position_[i] = glm::vec3(position[i]);
  // Islands: union-find over the links between bodies that are not fixed, each set named by
  // its smallest body (so the result does not depend on the links' order).
  std::vector<std::uint32_t> root(n);
  std::iota(root.begin(), root.end(), 0u);
  const auto find = [&](std::uint32_t b) {
    while (root[b] != b) {
      root[b] = root[root[b]];
      b = root[b];
    }
    return b;
  };
  const auto join = [&](std::uint32_t a, std::uint32_t b) {
    const std::uint32_t ra = find(a), rb = find(b);
    if (ra != rb) root[std::max(ra, rb)] = std::min(ra, rb);
  };
  for (const auto& [a, b] : links) {
    if (a == b || fixed_[a] != 0u || fixed_[b] != 0u) continue;
    join(a, b);
  }
  for (std::uint32_t b = 0; b < n; ++b)
    if (asleep_[b] != 0u) join(b, slept_with_[b]);
  std::vector<std::uint8_t> restful(n, 1u);  // per island root: every body may sleep now
  for (std::uint32_t b = 0; b < n; ++b) {
    if (fixed_[b] != 0u) continue;
    if (may_sleep_[b] == 0u || slow_time_[b] < settings_.time) restful[find(b)] = 0u;
  }
  std::vector<std::uint32_t> changed;
  for (std::uint32_t b = 0; b < n; ++b) {
    if (fixed_[b] != 0u) continue;
    const std::uint8_t sleeps = restful[find(b)];
    if (sleeps == asleep_[b]) continue;
    asleep_[b] = sleeps;
    if (sleeps == 0u) slow_time_[b] = 0.0f;
    changed.push_back(b);
  }
  for (std::uint32_t b = 0; b < n; ++b)
    if (asleep_[b] != 0u) slept_with_[b] = find(b);
  return changed;
}

std::vector<std::uint32_t> BodySleep::wake_all() {
  std::vector<std::uint32_t> woken;
  for (std::uint32_t b = 0; b < asleep_.size(); ++b) {
    if (asleep_[b] == 0u) continue;
    asleep_[b] = 0u;
    slow_time_[b] = 0.0f;
    woken.push_back(b);
  }
  return woken;
}

std::size_t BodySleep::asleep_count() const {
  return static_cast<std::size_t>(std::count(asleep_.begin(), asleep_.end(), std::uint8_t{1}));
}

std::vector<float> BodySleep::inverse_masses(std::size_t body) const {
  const gpu::ObjectInfo& o = objects_[body];
  if (asleep_[body] != 0u) return std::vector<float>(o.node_count, 0.0f);
  return {inverse_mass_.begin() + o.node_offset,
          inverse_mass_.begin() + o.node_offset + o.node_count};
}

}  // namespace deformcd
