#include <algorithm>

#include "deformcd/collision.h"
#include "deformcd/error.h"

namespace deformcd {

namespace {
struct NamedMethod {
  BroadPhase method;
  std::string_view name;
};
constexpr NamedMethod kMethods[] = {{BroadPhase::kNone, "none"},
                                    {BroadPhase::kBrute, "brute"},
                                    {BroadPhase::kOctree, "octree"},
                                    {BroadPhase::kOctreeCompact, "octree-compact"},
                                    {BroadPhase::kBvh, "bvh"}};
}  // namespace

BroadPhase parse_broadphase(std::string_view name) {
  for (const NamedMethod& m : kMethods) {
    if (m.name == name) return m.method;
  }
  std::string valid;
  for (const NamedMethod& m : kMethods)
    valid += (valid.empty() ? "" : ", ") + std::string(m.name);
  throw Error("unknown broad phase '" + std::string(name) + "' (valid: " + valid + ")");
}

std::string_view broadphase_name(BroadPhase method) {
  for (const NamedMethod& m : kMethods) {
    if (m.method == method) return m.name;
  }
  return "unknown";
}

const std::vector<std::string>& broadphase_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const NamedMethod& m : kMethods) {
      if (m.method != BroadPhase::kNone) out.emplace_back(m.name);
    }
    return out;
  }();
  return names;
}

}  // namespace deformcd
