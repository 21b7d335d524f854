// read_scene: JSON -> Scene, strictly (see json_fields.h).

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "deformcd/collision.h"
#include "deformcd/error.h"
#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "scene/duplicate_keys.h"
#include "scene/json_fields.h"

namespace deformcd {

namespace fs = std::filesystem;
using scene_detail::DuplicateKeyCheck;
using scene_detail::JsonFields;

namespace {

nlohmann::json parse_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), "cannot open scene file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  try {
    DuplicateKeyCheck check(file.string());
    return nlohmann::json::parse(text, std::ref(check));
  } catch (const nlohmann::json::parse_error& e) {
    // Turn the byte offset into a line number for the message.
    const std::size_t offset = std::min<std::size_t>(e.byte, text.size());
    const auto line = static_cast<std::size_t>(
        std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n') + 1);
    std::string what = e.what();
    const auto colon = what.find("parse error");
    throw InputError(file.string(), line,
                     "invalid JSON: " + (colon == std::string::npos ? what : what.substr(colon)));
  } catch (const nlohmann::json::out_of_range& e) {
    // A number no double holds (1e400): nlohmann reports it without a position.
    throw InputError(file.string(), std::string("invalid JSON: ") + e.what());
  }
}

// "1e+300": the value as written would be, not std::to_string's 301 digits.
std::string shortest(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// The simulation computes in float: a value must be finite (and, if positive, not zero) as a
// float, not only as a double (dt 1e300 is finite as a double and infinite as a float).
constexpr double kFloatMax = std::numeric_limits<float>::max();

double positive(JsonFields& f, const std::string& key, double fallback) {
  const double v = f.number(key).value_or(fallback);
  if (!(v > 0.0) || !std::isfinite(v)) {
    f.fail(key, "must be positive and finite, got " + shortest(v));
  }
  if (v > kFloatMax || !(static_cast<float>(v) > 0.0f)) {
    f.fail(key,
           "must be between 1.4e-45 and 3.4e+38 (the simulation computes in 32-bit float), "
           "got " +
               shortest(v));
  }
  return v;
}

double non_negative(JsonFields& f, const std::string& key, double fallback) {
  const double v = f.number(key).value_or(fallback);
  if (!(v >= 0.0) || !std::isfinite(v)) {
    f.fail(key, "must be finite and not negative, got " + shortest(v));
  }
  if (v > kFloatMax) {
    f.fail(key,
           "must be at most 3.4e+38 (the simulation computes in 32-bit float), got " + shortest(v));
  }
  return v;
}

SimulationSettings read_settings(JsonFields f) {
  SimulationSettings s;
  s.dt = positive(f, "dt", s.dt);
  s.substeps = f.integer("substeps").value_or(s.substeps);
  if (s.substeps < 1) f.fail("substeps", "must be at least 1");
  s.gravity = f.vec3("gravity").value_or(s.gravity);
  s.velocity_damping = non_negative(f, "velocity_damping", s.velocity_damping);
  s.frames = f.integer("frames").value_or(s.frames);
  if (s.frames < 1) f.fail("frames", "must be at least 1");
  f.reject_unknown();
  return s;
}

CollisionSettings read_collision(JsonFields f) {
  CollisionSettings c;
  c.broadphase = f.string("broadphase").value_or(c.broadphase);
  const auto& valid = known_broadphases();
  if (std::find(valid.begin(), valid.end(), c.broadphase) == valid.end()) {
    std::string list;
    for (const std::string& name : valid)
      list += (list.empty() ? "" : ", ") + name;
    f.fail("broadphase", "unknown broad phase '" + c.broadphase + "' (valid: " + list + ")");
  }
  c.self = f.boolean("self");
  f.reject_unknown();
  return c;
}

// Each key as ResponseSettings names it; check_response_settings's rules, reported at the key.
ResponseSettings read_response(JsonFields f) {
  ResponseSettings r;
  if (f.has("thickness")) r.thickness = static_cast<float>(positive(f, "thickness", 0.0));
  r.relative_thickness =
      static_cast<float>(positive(f, "relative_thickness", r.relative_thickness));
  r.friction_static = static_cast<float>(non_negative(f, "friction_static", r.friction_static));
  r.friction_dynamic = static_cast<float>(non_negative(f, "friction_dynamic", r.friction_dynamic));
  if (r.friction_dynamic > r.friction_static) {
    f.fail("friction_dynamic",
           "must not exceed friction_static (" + std::to_string(r.friction_static) + ")");
  }
  r.restitution = static_cast<float>(non_negative(f, "restitution", r.restitution));
  if (r.restitution > 1.0f) f.fail("restitution", "must be between 0 and 1");
  r.untangle_step = static_cast<float>(positive(f, "untangle_step", r.untangle_step));
  r.volume_floor = static_cast<float>(non_negative(f, "volume_floor", r.volume_floor));
  r.substep_motion = static_cast<float>(non_negative(f, "substep_motion", r.substep_motion));
  if (!(r.volume_floor < 1.0f)) f.fail("volume_floor", "must be below 1");
  r.iterations = f.integer("iterations").value_or(r.iterations);
  if (r.iterations < 1 || r.iterations > kMaxResponseIterations) {
    f.fail("iterations", "must be between 1 and " + std::to_string(kMaxResponseIterations));
  }
  if (auto sleep = f.object("sleep")) {
    SleepSettings z;
    z.speed = static_cast<float>(positive(*sleep, "speed", z.speed));
    z.time = static_cast<float>(positive(*sleep, "time", z.time));
    sleep->reject_unknown();
    r.sleep = z;
  }
  f.reject_unknown();
  return r;
}

MaterialSpec read_material(JsonFields f) {
  MaterialSpec m;
  if (f.has("density") && f.has("mass")) f.fail("mass", "give either density or mass, not both");
  if (f.has("density")) m.density = positive(f, "density", 0.0);
  if (f.has("mass")) m.mass = positive(f, "mass", 0.0);
  m.stiffness = positive(f, "stiffness", m.stiffness);
  m.damping = non_negative(f, "damping", m.damping);
  if (f.has("volume_stiffness")) m.volume_stiffness = non_negative(f, "volume_stiffness", 0.0);
  if (f.has("node_mass_floor")) {
    m.node_mass_floor = non_negative(f, "node_mass_floor", 0.0);
    if (*m.node_mass_floor > 1.0) f.fail("node_mass_floor", "must be between 0 and 1");
  }
  f.reject_unknown();
  return m;
}

FixedSpec read_fixed(JsonFields f) {
  FixedSpec fixed;
  if (const nlohmann::json* nodes = f.raw("nodes")) {
    if (!nodes->is_array()) f.fail("nodes", "expected an array of node indices");
    for (const auto& n : *nodes) {
      if (!n.is_number_unsigned()) f.fail("nodes", "expected non-negative integer node indices");
      const auto index = n.get<std::uint64_t>();
      if (index > std::numeric_limits<std::uint32_t>::max()) {
        f.fail("nodes", "node index " + std::to_string(index) + " is out of range");
      }
      fixed.nodes.push_back(static_cast<std::uint32_t>(index));
    }
  }
  if (auto box = f.object("box")) {
    Bounds b;
    b.min = box->vec3("min").value_or(glm::dvec3(0.0));
    b.max = box->vec3("max").value_or(glm::dvec3(0.0));
    if (!box->has("min") && !box->has("max")) f.fail("box", "needs min and max");
    box->reject_unknown();
    if (b.min.x > b.max.x || b.min.y > b.max.y || b.min.z > b.max.z) {
      f.fail("box", "min must not exceed max");
    }
    fixed.box = b;
  }
  f.reject_unknown();
  return fixed;
}

TetrahedralizeOptions read_meshing(JsonFields f) {
  TetrahedralizeOptions m = default_scene_meshing();
  if (f.has("quality")) {
    m.quality = f.number("quality");
    if (!(*m.quality >= 1.0)) {
      f.fail("quality",
             "must be at least 1 (a radius-edge ratio bound; TetGen's default 2.0, "
             "smaller is finer), got " +
                 std::to_string(*m.quality));
    }
  }
  if (f.has("max_volume")) m.max_volume = positive(f, "max_volume", 0.0);
  m.preserve_surface = f.boolean("preserve_surface").value_or(m.preserve_surface);
  f.reject_unknown();
  return m;
}

bool model_exists(const fs::path& model) {
  if (fs::is_regular_file(model)) return true;
  fs::path node = model;
  node += ".node";
  return fs::is_regular_file(node);
}

BodySpec read_body(JsonFields f, const fs::path& folder) {
  BodySpec b;
  const std::optional<std::string> model = f.string("model");
  if (!model) f.fail("model", "missing: every body needs a model (TetGen prefix or surface file)");
  b.model_as_written = *model;
  b.model = fs::path(*model).is_absolute() ? fs::path(*model) : folder / *model;
  b.model = b.model.lexically_normal();
  if (!model_exists(b.model)) {
    // The finer models of the scaling benchmark are generated, not shipped (about 100 MB).
    const std::string hint =
        b.model.parent_path().filename() == "fine"
            ? "; the fine models are generated, not shipped: run scripts/make_models.sh --fine"
            : "";
    // As written in the scene: the path resolved against the working directory would be
    // another string than the one to fix.
    f.fail("model", "no such model: '" + *model + "' (neither a file nor a TetGen prefix " +
                        "PREFIX.node, relative to the scene's folder)" + hint);
  }
  if (auto meshing = f.object("meshing")) {
    if (!is_surface_file(b.model)) {
      f.fail("meshing", "'" + *model +
                            "' is a TetGen mesh: meshing options apply to surface models "
                            "(.off .obj .stl .ply), which are tetrahedralized on loading");
    }
    b.meshing = read_meshing(*meshing);
  }
  b.name = f.string("name").value_or(b.model.filename().string());
  b.position = f.vec3("position").value_or(b.position);
  b.rotation = f.vec3("rotation").value_or(b.rotation);
  b.scale = f.vec3("scale", true).value_or(b.scale);
  if (b.scale.x <= 0 || b.scale.y <= 0 || b.scale.z <= 0) f.fail("scale", "must be positive");
  b.velocity = f.vec3("velocity").value_or(b.velocity);
  b.squash = f.vec3("squash", true).value_or(b.squash);
  if (b.squash.x <= 0 || b.squash.y <= 0 || b.squash.z <= 0) f.fail("squash", "must be positive");
  if (auto m = f.object("material")) b.material = read_material(*m);
  if (auto fixed = f.object("fixed")) b.fixed = read_fixed(*fixed);
  if (auto path = f.object("path")) {
    b.path_to = path->vec3("to");
    if (!b.path_to) path->fail("to", "missing: a path needs its end position 'to'");
    path->reject_unknown();
  }
  f.reject_unknown();
  return b;
}

}  // namespace

const std::vector<std::string>& known_broadphases() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out{std::string(broadphase_name(BroadPhase::kNone))};
    const std::vector<std::string>& detecting = broadphase_names();
    out.insert(out.end(), detecting.begin(), detecting.end());
    return out;
  }();
  return names;
}

Scene read_scene(const fs::path& file) {
  const nlohmann::json root = parse_file(file);
  JsonFields f(root, file.string(), "", "");
  Scene scene;
  scene.file = file;
  if (auto s = f.object("settings")) scene.settings = read_settings(*s);
  if (auto c = f.object("collision")) scene.collision = read_collision(*c);
  if (auto r = f.object("response")) scene.response = read_response(*r);
  const nlohmann::json* bodies = f.raw("bodies");
  if (!bodies || !bodies->is_array() || bodies->empty()) {
    f.fail("bodies", "expected a non-empty array of bodies");
  }
  const fs::path folder = file.parent_path();
  for (std::size_t i = 0; i < bodies->size(); ++i) {
    scene.bodies.push_back(read_body(
        JsonFields((*bodies)[i], file.string(), "/bodies/" + std::to_string(i), "bodies[]"),
        folder));
    // Outputs (positions, contacts) and messages name bodies: a name given twice is ambiguous.
    // Bodies left unnamed keep their model's name, shared or not (told apart by their index).
    const bool named = (*bodies)[i].contains("name");
    for (std::size_t j = 0; j < i; ++j) {
      if (scene.bodies[j].name != scene.bodies[i].name) continue;
      if (!named && !(*bodies)[j].contains("name")) continue;
      throw InputError(file.string(), "/bodies/" + std::to_string(i) + ": body name '" +
                                          scene.bodies[i].name + "' is also body " +
                                          std::to_string(j) +
                                          "'s (a body without \"name\" is named after its "
                                          "model): give each body its own name");
    }
  }
  f.reject_unknown();
  return scene;
}

}  // namespace deformcd
