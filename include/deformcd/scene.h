#pragma once
/// \file scene.h
/// Scenes: which bodies, where, of what material, and the simulation settings. Read from JSON
/// files (docs/scenes.md lists every key); every key is checked, and an unknown key, a wrong type
/// or a missing file is an error naming the key and the file.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <functional>

#include "deformcd/body.h"
#include "deformcd/response.h"
#include "deformcd/simulation_state.h"
#include "deformcd/tetrahedralize_options.h"

namespace deformcd {

/// Material of a body. Either density or total mass sets the node masses.
struct MaterialSpec {
  std::optional<double> density;  ///< kg/m^3; lumped per node from the tetrahedra
  std::optional<double> mass;     ///< kg, total; spread uniformly over the nodes
  /// Pa, Young's-modulus-like: a spring on an edge of tetrahedron t gets k = stiffness x
  /// volume(t) / rest_length^2, so the body's response does not depend on its meshing.
  double stiffness = 2.0e4;
  /// s, along each spring: damping coefficient = damping x the spring's stiffness.
  double damping = 2.0e-4;
  /// Pa: each tetrahedron resists volume change (and inversion) with this stiffness; unset
  /// means equal to `stiffness`; 0 is the paper's springs-only model.
  std::optional<double> volume_stiffness;
  /// Each node's lumped mass at least this share of the body's mean (BodyOptions::
  /// node_mass_floor; 0 keeps the pure lumping, at most 1). Unset: kResponseNodeMassFloor in a
  /// scene with a `response`, else 0 (node_mass_floor_on).
  std::optional<double> node_mass_floor;
};

/// Nodes held in place: listed by index, and/or every node inside a box (in scene coordinates,
/// after the body's transform).
struct FixedSpec {
  std::vector<std::uint32_t> nodes;  ///< node indices (local to the body)
  std::optional<Bounds> box;         ///< every node inside, after the body's transform
};

/// How a scene meshes a surface model unless its body's `meshing` says otherwise: TetGen's
/// quality bound (-q, radius-edge ratio 2.0) with the surface kept (-Y), so that the body's
/// surface is the model's and its interior has nodes. (Plain -p puts every node on the surface:
/// springs across the whole body, and a body that blows up at once.)
[[nodiscard]] inline TetrahedralizeOptions default_scene_meshing() {
  TetrahedralizeOptions options;
  options.quality = 2.0;
  options.preserve_surface = true;
  return options;
}

/// One body of a scene.
struct BodySpec {
  std::string name;              ///< defaults to the model's file name
  std::filesystem::path model;   ///< resolved against the scene file's folder
  std::string model_as_written;  ///< the scene's `model` string, for messages
  /// How `model` is tetrahedralized when it is a surface file (ignored for TetGen files).
  TetrahedralizeOptions meshing = default_scene_meshing();
  glm::dvec3 position{0.0};  ///< translation added to the model's coordinates
  glm::dvec3 rotation{0.0};  ///< degrees about x, then y, then z (applied before position)
  glm::dvec3 scale{1.0};     ///< applied first; rest shape (springs) uses it
  glm::dvec3 velocity{0.0};  ///< initial, m/s
  /// Initial deformation released at frame 0: node offsets from the body's centroid are
  /// multiplied by this after rest lengths are measured, so the body starts squashed and wobbles.
  glm::dvec3 squash{1.0};
  MaterialSpec material;  ///< the body's `material` object
  FixedSpec fixed;        ///< the body's `fixed` object
  /// The body is carried linearly from `position` to `*path_to` over the scene's frames, its
  /// mass-spring dynamics running relative to that motion.
  std::optional<glm::dvec3> path_to;
};

/// Time stepping.
struct SimulationSettings {
  double dt = 1.0 / 60.0;               ///< seconds per frame
  int substeps = 1;                     ///< integration steps per frame (step = dt / substeps)
  glm::dvec3 gravity{0.0, -9.81, 0.0};  ///< m/s^2
  double velocity_damping = 0.0;        ///< 1/s: every node's velocity decays by exp(-c t)
  int frames = 300;                     ///< default run length; paths span exactly this many frames
};

/// The `collision` section, consumed by the collision pipeline.
struct CollisionSettings {
  /// The fastest method by default; the paper's ("octree", and its baseline "brute") by name.
  std::string broadphase = "bvh";
  /// Also test each body against itself (and, with a response, keep its folds apart). Unset:
  /// on exactly when the scene has a `response` (WorldOptions::self_collision).
  std::optional<bool> self = std::nullopt;
};

/// A scene file as read by read_scene (docs/scenes.md lists its keys).
struct Scene {
  std::filesystem::path file;   ///< where it was read from (empty for scenes built in code)
  SimulationSettings settings;  ///< the `settings` object
  CollisionSettings collision;  ///< the `collision` object
  /// The `response` object: contact response on (`{}` = every default), else unset.
  std::optional<ResponseSettings> response;
  std::vector<BodySpec> bodies;  ///< the `bodies` array, in order
};

/// Whether the scene's bodies collide with themselves: its `collision.self`, or, unset, whether
/// it has a `response` (the rule of WorldOptions::self_collision).
[[nodiscard]] inline bool self_collision(const Scene& scene) {
  return self_collision_on(scene.collision.self, scene.response.has_value());
}

/// Loads a model file, e.g. read_tetgen (TetGen prefixes only).
using ModelLoader = std::function<TetMesh(const std::filesystem::path&)>;
/// Loads a model file, tetrahedralizing a surface file as its body's `meshing` says, e.g.
/// load_model (tetrahedralize.h, in deformcd::tetgen): every kind of model a scene may name.
using MeshingLoader =
    std::function<TetMesh(const std::filesystem::path&, const TetrahedralizeOptions&)>;

/// The broad-phase names a scene's `collision.broadphase` may take.
[[nodiscard]] const std::vector<std::string>& known_broadphases();

/// Every key read_scene accepts, as a dotted path: "settings", "settings.dt", "bodies[].name",
/// "bodies[].material.density", "response.sleep.speed" ("[]": an element of an array). It is
/// the reader's own list (the reader reads no other key and rejects the rest), so a reference
/// such as docs/scenes.md can be checked against it.
[[nodiscard]] const std::vector<std::string>& scene_keys();

/// Reads and checks a scene file. Model paths are resolved against the scene's folder and must
/// exist (as a file, or as a TetGen prefix with PREFIX.node). Throws InputError.
[[nodiscard]] Scene read_scene(const std::filesystem::path& file);

/// The scene's bodies, ready for a world: each model loaded (once per distinct file), scaled,
/// rotated and translated; masses from density (lumped) or total mass (uniform); rest lengths
/// measured in that pose; then the squash applied about the body's centroid; fixed nodes by index
/// and box; carry velocity = (path.to - position) / (frames x dt), so that the path spans `frames`.
/// Each distinct (model, meshing) is loaded once. Throws InputError naming the scene file and
/// the body.
[[nodiscard]] std::vector<BodyInit> make_scene_bodies(const Scene& scene, const MeshingLoader& load,
                                                      int frames);
/// The same with a loader that takes no meshing options (e.g. read_tetgen for scenes of TetGen
/// models).
[[nodiscard]] std::vector<BodyInit> make_scene_bodies(const Scene& scene, const ModelLoader& load,
                                                      int frames);

/// The scene's time-stepping settings in the form a world uses.
[[nodiscard]] StepSettings step_settings(const SimulationSettings& settings);

}  // namespace deformcd
