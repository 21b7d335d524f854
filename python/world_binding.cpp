// deformcd.World: a scene's bodies simulated and their collisions detected, stepped from
// Python; positions, velocities and contacts come back as NumPy arrays.

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "array_conversion.h"
#include "bindings.h"
#include "contact_arrays.h"
#include "deformcd/error.h"
#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "deformcd/world.h"
#include "deformcd/world_intersections.h"
#include "object_lock.h"

namespace deformcd::python {

namespace {

// Scene models as TetGen prefixes. Surface models would need TetGen in process, which is AGPL-3
// and kept out of this module (as of the core library).
TetMesh load_tetgen_model(const std::filesystem::path& path) {
  if (is_surface_file(path)) {
    throw InputError(path.string(),
                     "is a surface mesh; the Python module reads TetGen models only (make one "
                     "with `deformcd tetra " +
                         path.filename().string() + " -o PREFIX` and name PREFIX in the scene)");
  }
  return read_tetgen(path);
}

class PyWorld {
 public:
  static std::unique_ptr<PyWorld> from_scene(const std::filesystem::path& file,
                                             std::optional<int> frames, const std::string& backend,
                                             const std::string& broadphase, int threads,
                                             bool measure_stage_times) {
    const Scene scene = read_scene(file);
    const int run_frames = frames.value_or(scene.settings.frames);
    if (run_frames < 1) {
      throw py::value_error("from_scene: frames must be at least 1, got " +
                            std::to_string(run_frames));
    }
    WorldOptions options;
    options.backend = parse_backend(backend);
    options.broadphase = parse_broadphase(broadphase);
    options.cpu_threads = threads;
    options.measure_stage_times = measure_stage_times;
    options.self_collision = scene.collision.self;
    options.response = scene.response;
    auto world = std::make_unique<World>(make_scene_bodies(scene, load_tetgen_model, run_frames),
                                         step_settings(scene.settings), options);
    return std::unique_ptr<PyWorld>(new PyWorld(std::move(world), run_frames));
  }

  void step(int n) {
    if (n < 0) throw py::value_error("step: n must be 0 or more, got " + std::to_string(n));
    without_gil(mutex_, [&] {
      for (int i = 0; i < n; ++i)
        world_->step();
    });
  }
  void detect() {
    without_gil(mutex_, [&] { world_->detect_collisions(); });
  }

  py::array_t<float> positions(std::int64_t body) {
    const std::size_t b = existing_body(body, "positions");
    return vec3_array(without_gil(mutex_, [&] { return world_->positions(b); }));
  }
  py::array_t<float> velocities(std::int64_t body) {
    const std::size_t b = existing_body(body, "velocities");
    return vec3_array(without_gil(mutex_, [&] { return world_->velocities(b); }));
  }
  py::array_t<std::int64_t> faces(std::int64_t body) const {
    const gpu::ObjectInfo& o = world_->object(existing_body(body, "faces"));
    std::vector<Triangle> local(o.face_count);
    for (std::uint32_t f = 0; f < o.face_count; ++f) {
      const gpu::Face& g = world_->faces()[o.face_offset + f];
      local[f] = {g.a - o.node_offset, g.b - o.node_offset, g.c - o.node_offset};
    }
    return triangle_array(local);
  }
  py::dict contacts() {
    return contact_arrays(without_gil(mutex_, [&] { return world_->contacts(); }));
  }
  py::dict counts() {
    return counts_dict(without_gil(mutex_, [&] { return world_->collision_counts(); }));
  }
  py::dict last_frame_times() const {
    const FrameTimes& t = world_->last_frame_times();
    py::dict d;
    d["simulation_s"] = t.simulation_s;
    d["collision_s"] = t.collision_s;
    d["proximity_s"] = t.proximity_s;
    d["response_s"] = t.response_s;
    return d;
  }
  py::dict response_counts() {
    const ResponseCounts c = without_gil(mutex_, [&] { return world_->response_counts(); });
    py::dict d;
    d["vertex_face"] = c.vertex_face;
    d["edge_edge"] = c.edge_edge;
    d["untangle"] = c.untangle;
    d["penetrating"] = c.penetrating;
    d["between_bodies"] = c.between_bodies;
    d["searches"] = c.searches;
    d["widenings"] = c.widenings;
    d["self_searches"] = c.self_searches;
    d["substeps"] = c.substeps;
    d["iterations"] = c.iterations;
    d["asleep"] = c.asleep;
    return d;
  }
  py::dict intersection_census() {
    const IntersectionCensus c = without_gil(mutex_, [&] {
      // The counter holds the bodies' surfaces (topology only): made once, on first use.
      if (!census_) census_ = std::make_unique<WorldIntersections>(*world_);
      return census_->count();
    });
    py::dict d;
    d["between_pairs"] = c.between_pairs;
    d["self_pairs"] = c.self_pairs;
    d["inside_vertices"] = c.inside_vertices;
    return d;
  }
  py::array_t<bool> face_flags(const std::optional<std::int64_t>& body) {
    const std::optional<std::size_t> b =
        body ? std::optional<std::size_t>(existing_body(*body, "face_flags")) : std::nullopt;
    const std::vector<std::uint32_t> flags =
        without_gil(mutex_, [&] { return world_->face_flags(); });
    if (!b) return flag_array(flags, 0, flags.size());
    const gpu::ObjectInfo& o = world_->object(*b);
    return flag_array(flags, o.face_offset, o.face_count);
  }

  int frame() const { return world_->frame(); }
  int frames() const { return frames_; }
  std::size_t body_count() const { return world_->body_count(); }
  std::string body_name(std::int64_t body) const {
    return world_->body_name(existing_body(body, "body_name"));
  }
  bool asleep(std::int64_t body) const { return world_->asleep(existing_body(body, "asleep")); }
  std::vector<std::string> body_names() const {
    std::vector<std::string> names;
    for (std::size_t b = 0; b < world_->body_count(); ++b)
      names.push_back(world_->body_name(b));
    return names;
  }
  std::string broadphase() const { return std::string(broadphase_name(world_->broadphase())); }
  void set_broadphase(const std::string& name) {
    const BroadPhase method = parse_broadphase(name);
    const std::unique_lock<std::mutex> lock = lock_object(mutex_);
    world_->set_broadphase(method);
  }
  std::array<float, 3> gravity() const {
    const glm::vec3 g = world_->gravity();
    return {g.x, g.y, g.z};
  }
  void set_gravity(const std::array<float, 3>& g) {
    const std::unique_lock<std::mutex> lock = lock_object(mutex_);
    world_->set_gravity(glm::vec3(g[0], g[1], g[2]));
  }
  std::string backend() const { return std::string(world_->backend_name()); }
  std::string device() const { return world_->device(); }
  std::string notice() const { return world_->notice(); }
  double estimated_max_substep() const { return world_->estimated_max_substep(); }

  std::string repr() const {
    std::string names;
    for (const std::string& n : body_names())
      names += (names.empty() ? "" : ", ") + n;
    return "<deformcd.World: " + std::to_string(body_count()) + " bodies (" + names + "), frame " +
           std::to_string(frame()) + ", backend " + backend() + ", broadphase " + broadphase() +
           ">";
  }

 private:
  PyWorld(std::unique_ptr<World> world, int frames) : world_(std::move(world)), frames_(frames) {}

  std::size_t existing_body(std::int64_t body, const char* call) const {
    const std::size_t count = world_->body_count();
    if (body >= 0 && static_cast<std::size_t>(body) < count) return static_cast<std::size_t>(body);
    throw py::index_error(std::string(call) + ": body " + std::to_string(body) +
                          " does not exist (there are " + std::to_string(count) + " bodies)");
  }

  std::unique_ptr<World> world_;
  std::unique_ptr<WorldIntersections> census_;  // intersection_census()'s, once asked for
  int frames_;
  mutable std::mutex mutex_;
};

constexpr const char* kWorldDoc =
    R"doc(Deformable bodies (tetrahedral mass-spring systems) simulated, with their collisions detected
after each frame, as `deformcd run` does.

Made from a scene file (docs/scenes.md):

    w = deformcd.World.from_scene("scenes/phase2.json", frames=30, backend="cpu")
    w.step(30)
    p = w.positions(0)        # float32 (n, 3), body 0's nodes
    c = w.contacts()          # the last frame's contacts, as Detector.contacts()

Body i is mesh i of the contacts; a contact's face is the row of faces(i), its nodes index
positions(i). Calls run one at a time when shared between threads; step() and detect()
release the GIL.)doc";

constexpr const char* kFromSceneDoc =
    R"doc(Reads a scene file and builds its world at frame 0 (the initial pose).

Parameters
----------
path : str or os.PathLike
    The scene (JSON); its models are TetGen prefixes, relative to the scene's folder (surface
    models need the `deformcd` tool, which tetrahedralizes them: `deformcd tetra`).
frames : int, optional
    The run length the bodies' paths span (the scene's "frames" by default), as
    `deformcd run --frames`. step() may go past it.
backend : str
    "cpu", "gl" or "auto".
broadphase : str
    The collision broad phase run after each step ("bvh", "octree-compact", "octree",
    "brute", or "none" for no collision detection); every one finds the same contacts.
    The scene's own "collision.broadphase" is not used; its "collision.self" is (absent:
    on when the scene has a "response").
threads : int
    CPU threads; 0 uses every core. Results do not depend on it.
measure_stage_times : bool
    Time each stage of step() (see last_frame_times()); the world then waits for the backend
    after each stage, which on GL keeps the CPU from queueing the next frame's work.

Raises deformcd.InputError naming the file and the key for a bad scene or model,
deformcd.Error for a bad name, deformcd.GlError without OpenGL 4.3 for backend="gl".)doc";

}  // namespace

void bind_world(py::module_& m) {
  py::class_<PyWorld>(m, "World", kWorldDoc)
      .def_static("from_scene", &PyWorld::from_scene, py::arg("path"),
                  py::arg("frames") = py::none(), py::arg("backend") = "cpu",
                  py::arg("broadphase") = "bvh", py::arg("threads") = 0,
                  py::arg("measure_stage_times") = false, kFromSceneDoc)
      .def("step", &PyWorld::step, py::arg("n") = 1,
           "Advances n frames, each the scene's substeps and then a collision pass with\n"
           "`broadphase`. Raises deformcd.SimulationError naming the body and the frame when the\n"
           "simulation blows up.")
      .def("detect", &PyWorld::detect,
           "Runs a collision pass on the current positions now: at frame 0 (before any step(),\n"
           "contacts() is empty), or after changing `broadphase`.")
      .def("positions", &PyWorld::positions, py::arg("body"),
           "Body `body`'s node positions now: a float32 (n, 3) array, a copy read back from the\n"
           "backend.")
      .def("velocities", &PyWorld::velocities, py::arg("body"),
           "Body `body`'s node velocities now (m/s): a float32 (n, 3) array, a copy.")
      .def("faces", &PyWorld::faces, py::arg("body"),
           "Body `body`'s surface triangles: an int64 (m, 3) array of indices into\n"
           "positions(body). Contacts name a triangle by its row here.")
      .def("contacts", &PyWorld::contacts,
           "The intersecting surface-triangle pairs of the last collision pass, as a dict of\n"
           "NumPy arrays (see Detector.contacts(); body = body index, face = row of faces(body)).\n"
           "The same pairs as the line of that frame in `deformcd run --contacts`.")
      .def("counts", &PyWorld::counts, "Counts of the last collision pass (see Detector.counts()).")
      .def("last_frame_times", &PyWorld::last_frame_times,
           "Wall time of the last step()'s stages in seconds, a dict: simulation_s (substeps and\n"
           "the stability check), collision_s (bounds, broad and narrow phase), proximity_s and\n"
           "response_s (the contact response's pair search and projections). All 0 unless the\n"
           "world was made with measure_stage_times=True.")
      .def("response_counts", &PyWorld::response_counts,
           "The contact response's constraints at the end of the last step, a dict: vertex_face\n"
           "and edge_edge (proximity pairs), untangle (vertices of intersecting faces pushed\n"
           "out), penetrating (vertices inside another body pushed out), between_bodies (of\n"
           "those four, the constraints between two different bodies), searches, widenings,\n"
           "self_searches (bodies searched against themselves), substeps (the frame's), asleep\n"
           "(bodies). All 0 without the scene's response.")
      .def("intersection_census", &PyWorld::intersection_census,
           "The intersection census of the bodies now, a dict that folding cannot hide\n"
           "(deformcd/intersection_census.h): between_pairs (intersecting triangle pairs of two\n"
           "bodies), self_pairs (of a body with itself, whatever collision.self says) and\n"
           "inside_vertices (surface vertices inside another closed body). An exact CPU pass of\n"
           "its own on the positions now, one thread: about the cost of a detect() with\n"
           "self-collision.")
      .def("face_flags", &PyWorld::face_flags, py::arg("body") = py::none(),
           "A bool array, True for each surface triangle in a contact of the last pass: body\n"
           "`body`'s triangles, or with body=None every body's, one body after the other.")
      .def_property_readonly("frame", &PyWorld::frame, "Frames stepped so far (0 at the start).")
      .def_property_readonly("frames", &PyWorld::frames,
                             "The run length the bodies' paths span (from_scene's frames).")
      .def_property_readonly("body_count", &PyWorld::body_count, "Number of bodies.")
      .def("body_name", &PyWorld::body_name, py::arg("body"), "The body's name in the scene.")
      .def("asleep", &PyWorld::asleep, py::arg("body"),
           "Whether the body is asleep after the last step (the scene's response.sleep): its "
           "nodes hold still until a moving body touches its island.")
      .def_property_readonly("body_names", &PyWorld::body_names, "Every body's name, in order.")
      .def_property("broadphase", &PyWorld::broadphase, &PyWorld::set_broadphase,
                    "The broad phase step() runs after the simulation; may be set between steps.")
      .def_property("gravity", &PyWorld::gravity, &PyWorld::set_gravity,
                    "m/s^2, (x, y, z): the gravity the next step() applies; may be set between "
                    "steps (a tilting platform, a ramp of load); a change wakes sleeping bodies.")
      .def_property_readonly("backend", &PyWorld::backend, "\"cpu\" or \"gl\".")
      .def_property_readonly("device", &PyWorld::device,
                             "The GL renderer and version, or the CPU thread count.")
      .def_property_readonly("notice", &PyWorld::notice,
                             "What a user should know (why \"auto\" chose the CPU, a substep "
                             "longer than the stable one); may be empty.")
      .def_property_readonly("estimated_max_substep", &PyWorld::estimated_max_substep,
                             "Estimated largest stable substep in seconds (a conservative "
                             "bound).")
      .def("__repr__", &PyWorld::repr);
}

}  // namespace deformcd::python
