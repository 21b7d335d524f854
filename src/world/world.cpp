#include "deformcd/world.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "core/geometry.h"
#include "core/sim/stability_estimate.h"
#include "cpu/executor.h"
#include "deformcd/gl/context.h"
#include "deformcd/limits.h"
#include "detector/backend_choice.h"
#include "detector/detector_impl.h"
#include "world/contact_response.h"
#include "world/simulation_factory.h"

namespace deformcd {

namespace {

// Each body's surface as a detector mesh: its faces index the body's own nodes.
std::vector<CollisionMesh> surface_meshes(const std::vector<BodyInit>& bodies,
                                          bool self_collision) {
  std::vector<CollisionMesh> meshes;
  meshes.reserve(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    CollisionMesh m;
    m.vertex_count = static_cast<std::uint32_t>(bodies[b].body.positions.size());
    m.triangles.reserve(bodies[b].body.faces.size());
    for (const gpu::Face& f : bodies[b].body.faces)
      m.triangles.push_back({f.a, f.b, f.c});
    m.self_collision = self_collision;
    m.name = bodies[b].name.empty() ? "body " + std::to_string(b) : bodies[b].name;
    meshes.push_back(std::move(m));
  }
  return meshes;
}

}  // namespace

World::World(const std::vector<BodyInit>& bodies, const StepSettings& settings,
             const WorldOptions& options)
    : settings_(settings),
      check_interval_(std::max(1, options.stability_check_interval)),
      broadphase_(options.broadphase),
      measure_stage_times_(options.measure_stage_times) {
  if (bodies.empty()) throw Error("a world needs at least one body");
  if (!(settings.dt > 0.0f) || settings.substeps < 1) {
    throw Error("dt must be positive and substeps at least 1");
  }
  check_thread_count("threads", options.cpu_threads);
  const SimulationState state = assemble_simulation(bodies);
  objects_ = state.objects;
  names_ = state.body_names;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Bounds box = compute_bounds(bodies[b].body);
    body_sizes_.push_back(static_cast<float>(glm::length(box.max - box.min)));
    for (const gpu::Face& f : bodies[b].body.faces) {
      const std::uint32_t first = objects_[b].node_offset;
      faces_.push_back({f.a + first, f.b + first, f.c + first, static_cast<std::uint32_t>(b)});
    }
  }
  BackendChoice choice = choose_backend(options.backend, options.gl_context);
  owned_context_ = std::move(choice.owned_context);
  notice_ = std::move(choice.notice);
  executor_ = std::make_shared<cpu::Executor>(options.cpu_threads);
  backend_ = create_simulation(choice.kind, choice.context, executor_);
  max_stable_substep_ = sim::estimate_max_stable_substep(state);
  const double h = static_cast<double>(settings.dt) / settings.substeps;
  if (h > max_stable_substep_) {
    std::ostringstream msg;
    msg << "the substep (" << h << " s) is longer than the estimated stable one ("
        << max_stable_substep_ << " s, a conservative bound); if the simulation blows up, use "
        << "substeps >= " << suggested_substeps() << " or softer materials";
    notice_ += (notice_.empty() ? "" : "\n") + msg.str();
  }
  backend_->upload(state);
  // The detector reads the simulation's positions where they are: the CPU state's array, or
  // the GL position buffer (vec4 per node, xyz + inverse mass). The World checks them itself
  // (check_stability), so the detector does not.
  DetectorOptions detector_options;
  detector_options.broadphase = broadphase_;
  const bool self_collision =
      self_collision_on(options.self_collision, options.response.has_value());
  detector_ = std::unique_ptr<Detector>(
      new Detector(Detector::Impl::create(surface_meshes(bodies, self_collision), detector_options,
                                          choice.kind, choice.context, executor_, false)));
  // The detector reads the nodes where the simulation keeps them, in place.
  const sim::NodeBuffers nodes = backend_->node_buffers();
  for (std::size_t b = 0; b < objects_.size(); ++b) {
    const std::uint32_t first = objects_[b].node_offset;
    if (nodes.host_positions == nullptr) {
      detector_->set_positions(
          b, GlPositions{nodes.gl_positions, first * sizeof(glm::vec4), sizeof(glm::vec4)});
    } else {
      detector_->set_positions(b, HostPositions{&nodes.host_positions[first].x, sizeof(glm::vec4)});
    }
  }
  // The paper's octree cuts the start pose: build the hierarchies on it.
  detector_->prepare();
  if (options.response.has_value()) {
    response_ = std::make_unique<ContactResponse>(
        *options.response, bodies, state, settings, *backend_,
        create_response(choice.kind, choice.context, *backend_, executor_), executor_,
        self_collision);
  }
}

World::~World() = default;

void World::run_response(const std::function<void()>& stage) {
  try {
    stage();
  } catch (const SimulationError& e) {
    // The world's check names the frame and the suggested substeps; it finds the same node
    // unless the response met a position too large to subtract (finite, moving slowly).
    // The response checks the positions and velocities the integration gave it: what it finds
    // non-finite there was not made by contact forces (the bodies may be far apart).
    check_stability(frame_ + 1,
                    ", found by the contact response's check of what the integration gave it",
                    "response");
    BlowUpSite site = e.site();
    site.frame = frame_ + 1;
    throw SimulationError("the simulation became unstable by frame " + std::to_string(frame_ + 1) +
                              ": " + e.what() + ". " + advice(),
                          std::move(site));
  }
}

void World::step() {
  using Clock = std::chrono::steady_clock;
  using Seconds = std::chrono::duration<double>;
  double proximity_s = 0.0;
  double response_s = 0.0;
  if (response_) {
    // Untangling starts from the exact intersections of the pose the frame starts from.
    if (!detected_ && broadphase_ != BroadPhase::kNone) detect_collisions();
    const auto begin = Clock::now();
    run_response([&] {
      response_->begin_frame(*detector_,
                             detected_ ? detector_->contacts() : std::vector<Contact>{});
    });
    proximity_s = Seconds(Clock::now() - begin).count();
  }
  detector_->complete();  // before the positions move (a GL pass may rerun on them)
  const auto start = Clock::now();
  // The response may ask for more substeps than the scene's where its surfaces move fast.
  const int substeps = frame_substeps();
  const float h = settings_.dt / static_cast<float>(substeps);
  const sim::SubstepConstants constants{h, settings_.gravity,
                                        std::exp(-settings_.velocity_damping * h)};
  // A response stage after the substeps, its time (waiting for the backend on both sides)
  // counted as the response's, not the simulation's.
  const auto timed_response = [&](const std::function<void()>& stage) {
    if (measure_stage_times_) backend_->finish();
    const auto begin = Clock::now();
    run_response(stage);
    if (measure_stage_times_) {
      backend_->finish();
      response_s += Seconds(Clock::now() - begin).count();
    }
  };
  for (int s = 0; s < substeps; ++s) {
    backend_->substep(constants);
    if (response_) timed_response([&] { response_->project(h, s + 1 < substeps); });
  }
  if (response_) timed_response([&] { response_->end_frame(); });
  ++frame_;
  if (frame_ % check_interval_ == 0 || frame_ == 1) check_stability(frame_, "", "simulation");
  if (measure_stage_times_) backend_->finish();
  const auto simulated = Clock::now();
  if (broadphase_ != BroadPhase::kNone) {
    detect_collisions();
  } else {
    detected_ = false;
  }
  if (measure_stage_times_) {
    backend_->finish();
    last_times_.simulation_s = Seconds(simulated - start).count() - response_s;
    last_times_.collision_s = Seconds(Clock::now() - simulated).count();
    last_times_.proximity_s = proximity_s;
    last_times_.response_s = response_s;
  }
}

float World::contact_thickness(std::size_t body) const {
  return response_ ? response_->thickness(body) : 0.0f;
}

ResponseCounts World::response_counts() const {
  return response_ ? response_->counts() : ResponseCounts{};
}

bool World::asleep(std::size_t body) const {
  return response_ && response_->asleep(body);
}

void World::set_gravity(const glm::vec3& gravity) {
  if (!geom::is_finite(glm::dvec3(gravity))) {
    std::ostringstream msg;
    msg << "gravity (" << gravity.x << ", " << gravity.y << ", " << gravity.z
        << ") m/s^2: every component must be finite";
    throw Error(msg.str());
  }
  settings_.gravity = gravity;
  if (response_) response_->set_gravity(gravity);
}

void World::detect_collisions() {
  detector_->set_broadphase(broadphase_);
  detector_->detect();
  // Timed passes include a rerun after an overflow; otherwise the check waits until the next
  // step or read, so that the GPU can run on while the CPU queues the next frame.
  if (measure_stage_times_) detector_->complete();
  detected_ = broadphase_ != BroadPhase::kNone;
}

CollisionCounts World::collision_counts() const {
  if (!detected_) return {};
  return detector_->counts();
}

std::vector<Contact> World::contacts() const {
  if (!detected_) return {};
  return detector_->contacts();
}

std::vector<std::uint32_t> World::face_flags() const {
  if (!detected_) return std::vector<std::uint32_t>(faces_.size(), 0u);
  return detector_->face_flags();
}

std::uint32_t World::gl_face_flag_buffer() const {
  return detector_->gl_face_flag_buffer();
}

std::vector<gpu::Box> World::leaf_boxes() const {
  return detector_->leaf_boxes();
}

void World::finish() {
  backend_->finish();
}

int World::suggested_substeps() const {
  if (!std::isfinite(max_stable_substep_)) return 1;
  return static_cast<int>(std::ceil(settings_.dt / max_stable_substep_));
}

std::string World::advice() const {
  std::ostringstream msg;
  msg << "Use a smaller dt or more substeps (now dt = " << settings_.dt
      << " s, substeps = " << settings_.substeps << "; the estimated stable substep is "
      << max_stable_substep_ << " s, i.e. substeps >= " << suggested_substeps()
      << "), or softer springs";
  return msg.str();
}

int World::frame_substeps() const {
  return response_ ? response_->frame_substeps() : settings_.substeps;
}

void World::check_stability(int frame, const char* where, const char* stage) {
  std::vector<glm::vec4> positions, velocities;
  backend_->download_positions(positions);
  backend_->download_velocities(velocities);
  const float h = settings_.dt / static_cast<float>(frame_substeps());
  for (std::size_t b = 0; b < objects_.size(); ++b) {
    const gpu::ObjectInfo& o = objects_[b];
    for (std::uint32_t i = o.node_offset; i < o.node_offset + o.node_count; ++i) {
      const glm::vec3 p(positions[i]), v(velocities[i]);
      const bool finite = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) &&
                          std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
      const float travel = glm::length(v) * h;
      if (finite && travel <= 0.5f * body_sizes_[b]) continue;
      std::ostringstream msg;
      msg << "the simulation became unstable: body " << b << " ('" << names_[b] << "') by frame "
          << frame << ": node " << i - o.node_offset;
      if (!finite) {
        msg << " has a non-finite position or velocity";
      } else {
        msg << " moves " << travel << " per substep, more than half the body's size ("
            << body_sizes_[b] << ")";
      }
      msg << where << ". " << advice();
      throw SimulationError(msg.str(), {.stage = stage,
                                        .frame = frame,
                                        .body = static_cast<std::int64_t>(b),
                                        .body_name = names_[b],
                                        .node = static_cast<std::int64_t>(i - o.node_offset)});
    }
  }
}

std::vector<glm::vec3> World::positions(std::size_t body) const {
  std::vector<glm::vec4> all;
  backend_->download_positions(all);
  const gpu::ObjectInfo& o = objects_.at(body);
  return {all.begin() + o.node_offset, all.begin() + o.node_offset + o.node_count};
}

std::vector<glm::vec3> World::velocities(std::size_t body) const {
  std::vector<glm::vec4> all;
  backend_->download_velocities(all);
  const gpu::ObjectInfo& o = objects_.at(body);
  return {all.begin() + o.node_offset, all.begin() + o.node_offset + o.node_count};
}

std::string_view World::backend_name() const {
  return backend_->name();
}
std::string World::device() const {
  return backend_->device();
}
std::uint32_t World::gl_position_buffer() const {
  return backend_->node_buffers().gl_positions;
}

}  // namespace deformcd
