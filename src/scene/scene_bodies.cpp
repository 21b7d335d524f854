// Scene -> BodyInit: placing each model in the scene and giving it its material.

#include <cmath>
#include <map>
#include <optional>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat3x3.hpp>

#include "deformcd/error.h"
#include "deformcd/scene.h"

namespace deformcd {

namespace {

// Rotation by angles in degrees about x, then y, then z.
glm::dmat3 rotation_matrix(const glm::dvec3& degrees) {
  const glm::dvec3 r = glm::radians(degrees);
  const glm::dmat3 rx(1, 0, 0, 0, std::cos(r.x), std::sin(r.x), 0, -std::sin(r.x), std::cos(r.x));
  const glm::dmat3 ry(std::cos(r.y), 0, -std::sin(r.y), 0, 1, 0, std::sin(r.y), 0, std::cos(r.y));
  const glm::dmat3 rz(std::cos(r.z), std::sin(r.z), 0, -std::sin(r.z), std::cos(r.z), 0, 0, 0, 1);
  return rz * ry * rx;
}

TetMesh placed(TetMesh mesh, const BodySpec& spec) {
  const glm::dmat3 rotation = rotation_matrix(spec.rotation);
  for (glm::dvec3& p : mesh.nodes)
    p = rotation * (spec.scale * p) + spec.position;
  return mesh;
}

bool inside(const glm::dvec3& p, const Bounds& box) {
  return p.x >= box.min.x && p.y >= box.min.y && p.z >= box.min.z && p.x <= box.max.x &&
         p.y <= box.max.y && p.z <= box.max.z;
}

BodyInit make_body(const TetMesh& model, const BodySpec& spec, const Scene& scene, int frames,
                   const std::string& where) {
  const TetMesh mesh = placed(model, spec);
  BodyOptions options;
  if (spec.material.density) options.density = *spec.material.density;
  options.stiffness = spec.material.stiffness;
  options.node_mass_floor =
      node_mass_floor_on(spec.material.node_mass_floor, scene.response.has_value());
  BodyInit init;
  init.name = spec.name;
  init.body = build_body(mesh, options, where);
  Body& body = init.body;
  if (spec.material.mass) {  // uniform: every node gets an equal share of the total
    const double share = *spec.material.mass / static_cast<double>(body.node_mass.size());
    for (float& m : body.node_mass)
      m = static_cast<float>(share);
  }
  init.damping = static_cast<float>(spec.material.damping);
  init.volume_stiffness =
      static_cast<float>(spec.material.volume_stiffness.value_or(spec.material.stiffness));
  if (spec.path_to) {
    const double duration = frames * scene.settings.dt;
    init.carry_velocity = glm::vec3((*spec.path_to - spec.position) / duration);
  }

  for (std::uint32_t n : spec.fixed.nodes) {
    if (n >= mesh.nodes.size()) {
      throw InputError(where, "fixed node " + std::to_string(n) + " out of range (the model has " +
                                  std::to_string(mesh.nodes.size()) + " nodes, 0-based)");
    }
    init.fixed.push_back(n);
  }
  if (spec.fixed.box) {
    std::size_t selected = 0;
    for (std::uint32_t n = 0; n < mesh.nodes.size(); ++n) {
      if (inside(mesh.nodes[n], *spec.fixed.box)) {
        init.fixed.push_back(n);
        ++selected;
      }
    }
    if (selected == 0) throw InputError(where, "the fixed box contains no node of the body");
  }

  // The squash deforms the start pose only: springs keep the rest lengths measured above.
  glm::dvec3 centroid(0.0);
  for (const glm::vec4& p : body.positions)
    centroid += glm::dvec3(p);
  centroid /= static_cast<double>(body.positions.size());
  for (glm::vec4& p : body.positions) {
    p = glm::vec4(glm::vec3(centroid + spec.squash * (glm::dvec3(p) - centroid)), p.w);
  }
  for (glm::vec4& v : body.velocities)
    v = glm::vec4(glm::vec3(spec.velocity), 0.0f);
  update_face_normals(body);
  return init;
}

// The model of body `i`, an error in it named with the scene and the key that named it (the
// model's own message, e.g. "bunny.off:12: ...", says what is wrong in the model).
TetMesh load_model_of(const Scene& scene, std::size_t i, const MeshingLoader& load) {
  const BodySpec& spec = scene.bodies[i];
  try {
    return load(spec.model, spec.meshing);
  } catch (const InputError& e) {
    throw InputError(scene.file.string(), "/bodies/" + std::to_string(i) + "/model ('" +
                                              spec.model_as_written + "'): " + e.what());
  }
}

}  // namespace

std::vector<BodyInit> make_scene_bodies(const Scene& scene, const MeshingLoader& load, int frames) {
  if (frames < 1) throw InputError(scene.file.string(), "frames must be at least 1");
  // Each distinct model loaded once (per meshing, for surfaces).
  using Key = std::tuple<std::filesystem::path, std::optional<double>, std::optional<double>, bool>;
  std::map<Key, TetMesh> models;
  std::vector<BodyInit> bodies;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& spec = scene.bodies[i];
    const std::string where =
        scene.file.string() + ": body " + std::to_string(i) + " ('" + spec.name + "')";
    const Key key{spec.model, spec.meshing.quality, spec.meshing.max_volume,
                  spec.meshing.preserve_surface};
    auto it = models.find(key);
    if (it == models.end()) it = models.emplace(key, load_model_of(scene, i, load)).first;
    bodies.push_back(make_body(it->second, spec, scene, frames, where));
  }
  return bodies;
}

std::vector<BodyInit> make_scene_bodies(const Scene& scene, const ModelLoader& load, int frames) {
  return make_scene_bodies(
      scene,
      MeshingLoader([&load](const std::filesystem::path& model, const TetrahedralizeOptions&) {
        return load(model);
      }),
      frames);
}

StepSettings step_settings(const SimulationSettings& s) {
  StepSettings out;
  out.dt = static_cast<float>(s.dt);
  out.substeps = s.substeps;
  out.gravity = glm::vec3(s.gravity);
  out.velocity_damping = static_cast<float>(s.velocity_damping);
  return out;
}

}  // namespace deformcd
