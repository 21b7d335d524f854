#include "deformcd/world.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "backend_factory.h"
#include "core/collision/collision_backend.h"
#include "core/collision/contacts.h"
#include "core/sim/stability_estimate.h"
#include "deformcd/gl/context.h"

namespace deformcd {

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
  const WorldState state = assemble_world(bodies, {.self_collision = options.self_collision});
  objects_ = state.objects;
  names_ = state.body_names;
  faces_ = state.faces;
  for (const BodyInit& b : bodies) {
    const Bounds box = compute_bounds(b.body);
    body_sizes_.push_back(static_cast<float>(glm::length(box.max - box.min)));
  }
  CreatedBackend created = create_backend(options);
  owned_context_ = std::move(created.owned_context);
  backend_ = std::move(created.backend);
  collision_ = std::move(created.collision);
  notice_ = std::move(created.notice);
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
  collision_->upload(state);
}

World::~World() = default;

void World::step() {
  complete_collision_pass();  // before the positions move
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const float h = settings_.dt / static_cast<float>(settings_.substeps);
  const sim::SubstepConstants constants{h, settings_.gravity,
                                        std::exp(-settings_.velocity_damping * h)};
  for (int s = 0; s < settings_.substeps; ++s)
    backend_->substep(constants);
  ++frame_;
  if (frame_ % check_interval_ == 0 || frame_ == 1) check_stability();
  if (measure_stage_times_) backend_->finish();
  const auto simulated = Clock::now();
  if (broadphase_ != BroadPhase::kNone) {
    detect_collisions();
  } else {
    detected_ = false;
  }
  if (measure_stage_times_) {
    backend_->finish();
    last_times_.simulation_s = std::chrono::duration<double>(simulated - start).count();
    last_times_.collision_s = std::chrono::duration<double>(Clock::now() - simulated).count();
  }
}

void World::complete_collision_pass() const {
  if (!pass_pending_) return;
  collision_->complete_pass();
  pass_pending_ = false;
}

void World::detect_collisions() {
  complete_collision_pass();
  collision_->detect(broadphase_);
  pass_pending_ = true;
  // Timed passes include a rerun after an overflow; otherwise the check waits until the next
  // step or read, so that the GPU can run on while the CPU queues the next frame.
  if (measure_stage_times_) complete_collision_pass();
  detected_ = broadphase_ != BroadPhase::kNone;
}

CollisionCounts World::collision_counts() const {
  if (!detected_) return {};
  complete_collision_pass();
  const gpu::CollisionCounters c = collision_->counters();
  return {c.face_pairs, c.box_pairs, c.colliding_faces, c.candidates};
}

std::vector<Contact> World::contacts() const {
  if (!detected_) return {};
  complete_collision_pass();
  std::vector<gpu::FacePair> pairs;
  collision_->download_face_pairs(pairs);
  return collision::make_contacts(pairs, faces_, objects_);
}

std::vector<std::uint32_t> World::face_flags() const {
  if (!detected_) return std::vector<std::uint32_t>(faces_.size(), 0u);
  complete_collision_pass();
  std::vector<std::uint32_t> flags;
  collision_->download_face_flags(flags);
  flags.resize(faces_.size());  // a GL buffer holds at least one element
  return flags;
}

std::uint32_t World::gl_face_flag_buffer() const {
  return collision_->gl_face_flag_buffer();
}

std::vector<gpu::Box> World::leaf_boxes() const {
  complete_collision_pass();
  std::vector<gpu::Box> boxes;
  collision_->download_boxes(boxes);
  boxes.resize(objects_.size() * gpu::kLeafBoxesPerBody);
  return boxes;
}

void World::finish() {
  backend_->finish();
}

int World::suggested_substeps() const {
  if (!std::isfinite(max_stable_substep_)) return 1;
  return static_cast<int>(std::ceil(settings_.dt / max_stable_substep_));
}

void World::check_stability() {
  std::vector<glm::vec4> positions, velocities;
  backend_->download_positions(positions);
  backend_->download_velocities(velocities);
  const float h = settings_.dt / static_cast<float>(settings_.substeps);
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
          << frame_ << ": node " << i - o.node_offset;
      if (!finite) {
        msg << " has a non-finite position or velocity";
      } else {
        msg << " moves " << travel << " per substep, more than half the body's size ("
            << body_sizes_[b] << ")";
      }
      msg << ". Use a smaller dt or more substeps (now dt = " << settings_.dt
          << " s, substeps = " << settings_.substeps << "; the estimated stable substep is "
          << max_stable_substep_ << " s, i.e. substeps >= " << suggested_substeps()
          << "), or softer springs";
      throw SimulationError(msg.str());
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
  return backend_->gl_position_buffer();
}

}  // namespace deformcd
