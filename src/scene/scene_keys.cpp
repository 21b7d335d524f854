#include "scene/scene_keys.h"

#include <stdexcept>
#include <vector>

#include "deformcd/scene.h"

namespace deformcd {
namespace scene_detail {
namespace {

struct ObjectKeys {
  std::string_view path;
  std::vector<std::string> keys;
};

// In the order of docs/scenes.md. A key added to the reader must be added here first: the
// reader cannot read it otherwise (JsonFields checks), and the docs test then asks for its row.
const std::vector<ObjectKeys>& table() {
  static const std::vector<ObjectKeys> objects = {
      {"", {"settings", "collision", "response", "bodies"}},
      {"settings", {"dt", "substeps", "gravity", "velocity_damping", "frames"}},
      {"collision", {"broadphase", "self"}},
      {"response",
       {"thickness", "relative_thickness", "friction_static", "friction_dynamic", "restitution",
        "untangle_step", "volume_floor", "substep_motion", "iterations", "sleep"}},
      {"response.sleep", {"speed", "time"}},
      {"bodies[]",
       {"name", "model", "meshing", "position", "rotation", "scale", "velocity", "squash",
        "material", "fixed", "path"}},
      {"bodies[].meshing", {"quality", "max_volume", "preserve_surface"}},
      {"bodies[].material",
       {"density", "mass", "stiffness", "damping", "volume_stiffness", "node_mass_floor"}},
      {"bodies[].fixed", {"nodes", "box"}},
      {"bodies[].fixed.box", {"min", "max"}},
      {"bodies[].path", {"to"}},
  };
  return objects;
}

}  // namespace

std::span<const std::string> keys_at(std::string_view path) {
  for (const ObjectKeys& object : table()) {
    if (object.path == path) return object.keys;
  }
  throw std::logic_error("scene_keys: no key table for the object '" + std::string(path) + "'");
}

}  // namespace scene_detail

const std::vector<std::string>& scene_keys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> out;
    for (const scene_detail::ObjectKeys& object : scene_detail::table()) {
      for (const std::string& key : object.keys) {
        out.push_back(object.path.empty() ? key : std::string(object.path) + "." + key);
      }
    }
    return out;
  }();
  return keys;
}

}  // namespace deformcd
