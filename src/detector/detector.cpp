#include "deformcd/detector.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include <glm/common.hpp>

#include "core/collision/contacts.h"
#include "core/collision/primitive_distance.h"
#include "core/geometry.h"
#include "cpu/cpu_collision.h"
#include "cpu/parallel_for.h"
#include "deformcd/error.h"
#include "deformcd/gl/context.h"  // declarations only: fine without the GL backend
#include "deformcd/limits.h"
#include "detector/backend_choice.h"
#include "detector/detector_impl.h"

namespace deformcd {

namespace {

using collision::PositionSource;

const std::string& label_of(const collision::CollisionData& data, std::size_t mesh) {
  return data.mesh_names[mesh];
}

std::string describe(const glm::vec3& p) {
  std::ostringstream out;
  out << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return out.str();
}

}  // namespace

std::unique_ptr<Detector::Impl> Detector::Impl::create(std::vector<CollisionMesh> meshes,
                                                       const DetectorOptions& options,
                                                       BackendKind kind, gl::Context* context,
                                                       std::shared_ptr<cpu::Executor> executor,
                                                       bool check_positions) {
  auto impl = std::make_unique<Impl>();
  impl->data = collision::lay_out_meshes(
      meshes, options.mesh_pairs.has_value() ? &*options.mesh_pairs : nullptr);
  impl->vertex_first = collision::vertex_firsts(impl->data);
  impl->meshes = std::move(meshes);
  impl->broadphase = options.broadphase;
  impl->check_positions = check_positions;
  impl->sources.resize(impl->meshes.size());
  for (std::size_t m = 0; m < impl->meshes.size(); ++m)
    impl->sources[m].vertex_count = impl->meshes[m].vertex_count;
  if (kind == BackendKind::kGl) {
    impl->context = context;
    impl->backend = make_gl_collision(*context, executor);
  } else {
    impl->backend = std::make_unique<cpu::CpuCollision>(executor);
  }
  impl->executor = std::move(executor);
  return impl;
}

void Detector::Impl::make_current() const {
  if (context != nullptr) context->make_current();
}

void Detector::Impl::push_sources(std::vector<PositionSource> next) {
  make_current();
  backend->set_positions(next);  // checks what only the backend can (a GL buffer's size)
  sources = std::move(next);
}

void Detector::Impl::require_mesh(std::size_t mesh, const std::string& operation) const {
  if (mesh >= meshes.size()) {
    throw InputError(operation, "mesh " + std::to_string(mesh) + " does not exist (there are " +
                                    std::to_string(meshes.size()) + " meshes)");
  }
}

void Detector::Impl::require_positions() const {
  for (std::size_t m = 0; m < sources.size(); ++m) {
    if (sources[m].kind == PositionSource::Kind::kNone) {
      throw InputError(label_of(data, m), "has no positions (call set_positions first)");
    }
  }
}

// Host arrays are checked here, on the host, before anything changes; GL buffers by the backend.
void Detector::Impl::check_finite() {
  for (std::size_t m = 0; m < sources.size(); ++m) {
    const PositionSource& s = sources[m];
    if (s.kind != PositionSource::Kind::kHost) continue;
    const std::size_t stride = s.stride_bytes / sizeof(float);
    glm::vec3 low(kMaxCoordinate);
    glm::vec3 high(-kMaxCoordinate);
    for (std::uint32_t v = 0; v < s.vertex_count; ++v) {
      const float* p = s.host + v * stride;
      const glm::vec3 x(p[0], p[1], p[2]);
      if (!(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z))) {
        throw InputError(label_of(data, m), "vertex " + std::to_string(v) +
                                                " has a non-finite position " + describe(x));
      }
      if (std::abs(x.x) > kMaxCoordinate || std::abs(x.y) > kMaxCoordinate ||
          std::abs(x.z) > kMaxCoordinate) {
        throw InputError(label_of(data, m),
                         "vertex " + std::to_string(v) + " has position " + describe(x) +
                             ", outside +-1e9 (deformcd::kMaxCoordinate), the range in which "
                             "contacts do not depend on the units");
      }
      low = glm::min(low, x);
      high = glm::max(high, x);
    }
    const glm::vec3 side = high - low;
    const float extent = std::max(side.x, std::max(side.y, side.z));
    if (s.vertex_count > 0 && extent > 0.0f && extent < kMinMeshExtent) {
      throw InputError(label_of(data, m),
                       "spans only " + describe(side) +
                           ", below 1e-10 (deformcd::kMinMeshExtent), the smallest size at which "
                           "contacts do not depend on the units: give it in smaller units");
    }
  }
  std::uint32_t mesh = 0;
  std::uint32_t vertex = 0;
  make_current();
  if (backend->find_non_finite(mesh, vertex)) {
    const std::vector<glm::vec3> p = backend->read_positions(mesh);
    throw InputError(label_of(data, mesh), "vertex " + std::to_string(vertex) +
                                               " has a non-finite position " +
                                               describe(p.at(vertex)) + " (in its GL buffer)");
  }
}

std::vector<collision::MeshVertices> Detector::Impl::host_vertices(
    std::vector<std::vector<glm::vec3>>& read_back) {
  read_back.assign(sources.size(), {});
  std::vector<collision::MeshVertices> pose(sources.size());
  for (std::size_t m = 0; m < sources.size(); ++m) {
    const PositionSource& s = sources[m];
    if (s.kind == PositionSource::Kind::kHost) {
      pose[m] = {s.host, static_cast<std::uint32_t>(s.stride_bytes / sizeof(float))};
    } else {
      make_current();
      read_back[m] = backend->read_positions(static_cast<std::uint32_t>(m));
      pose[m] = {&read_back[m][0].x, 3u};
    }
  }
  return pose;
}

// The hierarchies are built on the positions now: host arrays in place, GL buffers read back.
void Detector::Impl::prepare() {
  require_positions();
  check_finite();
  std::vector<std::vector<glm::vec3>> read_back;
  const std::vector<collision::MeshVertices> pose = host_vertices(read_back);
  collision::CollisionData next = data;
  collision::build_hierarchies(next, pose.data());
  make_current();
  backend->upload(next);
  data = std::move(next);
  prepared = true;
  detected = false;
  pending = false;
}

void Detector::Impl::complete() {
  if (!pending) return;
  make_current();
  backend->complete_pass();
  pending = false;
}

Detector::Detector(std::vector<CollisionMesh> meshes, const DetectorOptions& options) {
  check_thread_count("threads", options.threads);
  BackendChoice choice = choose_backend(options.backend, options.gl_context);
  impl_ = Impl::create(std::move(meshes), options, choice.kind, choice.context,
                       std::make_shared<cpu::Executor>(options.threads), true);
  impl_->owned_context = std::move(choice.owned_context);
  impl_->notice = std::move(choice.notice);
}

Detector::Detector(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Detector::~Detector() {
  if (!impl_) return;
  try {
    impl_->make_current();  // GL objects are deleted in their context
  } catch (const GlError&) {
    // A destructor must not throw. Deleting the GL objects in whatever context is current
    // could delete another context's objects of the same names: leave them to their context
    // (they go with it when the detector owns it), at the cost of the backend's host memory.
    (void)impl_->backend.release();
  }
}
Detector::Detector(Detector&&) noexcept = default;
Detector& Detector::operator=(Detector&&) noexcept = default;

std::size_t Detector::mesh_count() const {
  return impl_->meshes.size();
}
const CollisionMesh& Detector::mesh(std::size_t mesh) const {
  return impl_->meshes.at(mesh);
}
std::uint32_t Detector::face_offset(std::size_t mesh) const {
  return impl_->data.meshes.at(mesh).face_offset;
}
std::size_t Detector::face_count() const {
  return impl_->data.faces.size();
}

void Detector::set_positions(std::size_t mesh, const HostPositions& positions) {
  impl_->require_mesh(mesh, "set_positions");
  const std::string& label = label_of(impl_->data, mesh);
  if (positions.data == nullptr) throw InputError(label, "positions: null array");
  if (positions.stride_bytes < 3 * sizeof(float) || positions.stride_bytes % sizeof(float) != 0) {
    throw InputError(label, "positions: stride of " + std::to_string(positions.stride_bytes) +
                                " bytes; it must be a multiple of 4, at least 12 (x, y, z)");
  }
  std::vector<PositionSource> next = impl_->sources;
  PositionSource& s = next[mesh];
  s.kind = PositionSource::Kind::kHost;
  s.host = positions.data;
  s.gl_buffer = 0;
  s.offset_bytes = 0;
  s.stride_bytes = positions.stride_bytes;
  impl_->push_sources(std::move(next));
}

void Detector::set_positions(std::size_t mesh, std::span<const glm::vec3> v) {
  if (mesh < impl_->meshes.size() && v.size() != impl_->meshes[mesh].vertex_count) {
    throw InputError(label_of(impl_->data, mesh),
                     "positions: " + std::to_string(v.size()) + " given, the mesh has " +
                         std::to_string(impl_->meshes[mesh].vertex_count) + " vertices");
  }
  set_positions(mesh, HostPositions{v.empty() ? nullptr : &v[0].x, sizeof(glm::vec3)});
}

void Detector::set_positions(std::size_t mesh, const GlPositions& positions) {
  impl_->require_mesh(mesh, "set_positions");
  const std::string& label = label_of(impl_->data, mesh);
  if (impl_->backend->name() != "gl") {
    throw Error(label + ": positions in a GL buffer need the GL backend (this detector runs on " +
                std::string(impl_->backend->name()) + ")");
  }
  if (positions.buffer == 0) throw InputError(label, "positions: GL buffer 0");
  if (positions.offset_bytes % sizeof(float) != 0 || positions.stride_bytes % sizeof(float) != 0 ||
      positions.stride_bytes < 3 * sizeof(float)) {
    throw InputError(label, "positions: GL buffer offset " +
                                std::to_string(positions.offset_bytes) + " and stride " +
                                std::to_string(positions.stride_bytes) +
                                " bytes; both must be multiples of 4, the stride at least 12");
  }
  std::vector<PositionSource> next = impl_->sources;
  PositionSource& s = next[mesh];
  s.kind = PositionSource::Kind::kGl;
  s.host = nullptr;
  s.gl_buffer = positions.buffer;
  s.offset_bytes = positions.offset_bytes;
  s.stride_bytes = positions.stride_bytes;
  try {
    impl_->push_sources(std::move(next));
  } catch (const GlError&) {
    throw;  // the device's limits, not the caller's input
  } catch (const InputError&) {
    throw;
  } catch (const Error& e) {
    // The backend checked what only GL can tell (the buffer exists, is large enough).
    throw InputError(label, std::string("positions: ") + e.what());
  }
}

BroadPhase Detector::broadphase() const {
  return impl_->broadphase;
}
void Detector::set_broadphase(BroadPhase method) {
  impl_->broadphase = method;
}

void Detector::prepare() {
  impl_->complete();
  impl_->prepare();
}

void Detector::detect() {
  Impl& d = *impl_;
  d.require_positions();
  d.complete();
  if (d.check_positions) d.check_finite();
  if (!d.prepared) d.prepare();
  d.make_current();
  d.backend->detect(d.broadphase);
  d.pending = true;
  d.detected = d.broadphase != BroadPhase::kNone;
}

void Detector::complete() {
  impl_->complete();
}

std::vector<Contact> Detector::contacts() const {
  if (!impl_->detected) return {};
  impl_->complete();
  std::vector<gpu::FacePair> pairs;
  impl_->backend->download_face_pairs(pairs);
  return collision::make_contacts(pairs, impl_->data.faces, impl_->data.meshes);
}

// The detector's pairs from the search's candidates: their distances from `distances` (the
// CPU search's) or, when that is empty (a GL search), from `pose`.
static std::vector<ProximityPair> to_proximity_pairs(
    Detector::Impl& d, const std::vector<collision::ProximityCandidate>& found,
    const std::vector<float>& distances, const std::vector<collision::MeshVertices>& pose) {
  std::vector<ProximityPair> out(found.size());
  d.executor->run([&] {
    cpu::parallel_for(found.size(), [&](std::size_t i) {
      const collision::ProximityCandidate& c = found[i];
      ProximityPair& p = out[i];
      p.kind = c.kind == gpu::kContactEdgeEdge ? ProximityPair::Kind::kEdgeEdge
                                               : ProximityPair::Kind::kVertexTriangle;
      p.mesh_a = c.mesh_a;
      p.mesh_b = c.mesh_b;
      p.vertices = c.vertices;
      p.triangle =
          c.kind == gpu::kContactEdgeEdge ? 0u : c.face_b - d.data.meshes[c.mesh_b].face_offset;
      if (!distances.empty()) {
        p.distance = distances[i];
        return;
      }
      glm::vec3 x[4];
      for (std::uint32_t k = 0; k < 4u; ++k) {
        const bool side_a = k < (c.kind == gpu::kContactEdgeEdge ? 2u : 1u);
        x[k] = collision::vertex_position(pose.data(), side_a ? c.mesh_a : c.mesh_b, c.vertices[k]);
      }
      p.distance = collision::primitive_distance(c.kind, x);
    });
  });
  return out;
}

std::vector<ProximityPair> Detector::find_proximity(std::span<const float> reach,
                                                    std::span<const glm::vec3> motion,
                                                    std::span<const std::uint8_t> still,
                                                    const ProximityPairs& pairs) {
  Impl& d = *impl_;
  const std::size_t vertices = d.vertex_first.back();
  // One reach per mesh, or one per vertex: per vertex from here on.
  if (reach.size() != d.meshes.size() && reach.size() != vertices) {
    throw InputError("find_proximity",
                     "takes one reach per mesh (" + std::to_string(d.meshes.size()) +
                         ") or per vertex of every mesh (" + std::to_string(vertices) + "), not " +
                         std::to_string(reach.size()));
  }
  const bool per_mesh = reach.size() == d.meshes.size() && reach.size() != vertices;
  std::vector<float> vertex_reach;
  std::vector<const float*> reach_of(d.meshes.size());
  if (per_mesh) {
    vertex_reach.reserve(vertices);
    for (std::size_t m = 0; m < d.meshes.size(); ++m)
      vertex_reach.insert(vertex_reach.end(), d.meshes[m].vertex_count, reach[m]);
    reach = vertex_reach;
  }
  for (std::size_t m = 0; m < d.meshes.size(); ++m) {
    const std::uint32_t first = d.vertex_first[m];
    reach_of[m] = reach.data() + first;
    for (std::uint32_t v = 0; v < d.meshes[m].vertex_count; ++v) {
      const float r = reach[first + v];
      if (!(r >= 0.0f) || !std::isfinite(r)) {
        throw InputError(label_of(d.data, m),
                         (per_mesh ? std::string() : "vertex " + std::to_string(v) + " ") +
                             "has a reach of " + std::to_string(r) +
                             " (find_proximity wants a finite value >= 0)");
      }
    }
  }
  if (!motion.empty() && motion.size() != vertices) {
    throw InputError("find_proximity", "takes one motion per vertex of every mesh (or none): " +
                                           std::to_string(vertices) + " expected, " +
                                           std::to_string(motion.size()) + " given");
  }
  std::vector<collision::MeshVertices> motion_of(motion.empty() ? 0u : d.meshes.size());
  for (std::size_t m = 0; m < motion_of.size(); ++m) {
    const std::uint32_t first = d.vertex_first[m];
    motion_of[m] = {&motion[first].x, 3u};
    for (std::uint32_t v = 0; v < d.meshes[m].vertex_count; ++v) {
      const glm::vec3& mv = motion[first + v];
      if (!geom::is_finite(glm::dvec3(mv))) {
        throw InputError(label_of(d.data, m), "vertex " + std::to_string(v) +
                                                  " has a non-finite motion " + describe(mv));
      }
    }
  }
  if (!still.empty() && still.size() != d.meshes.size()) {
    throw InputError("find_proximity", "takes one still flag per mesh (" +
                                           std::to_string(d.meshes.size()) + ") or none, not " +
                                           std::to_string(still.size()));
  }
  if (!pairs.within.empty() && pairs.within.size() != d.meshes.size()) {
    throw InputError("find_proximity", "takes one self-pair flag per mesh (" +
                                           std::to_string(d.meshes.size()) + ") or none, not " +
                                           std::to_string(pairs.within.size()));
  }
  std::vector<std::uint32_t> mesh_pairs =
      collision::searched_mesh_pairs(d.data, still, pairs.between, pairs.within);
  d.require_positions();
  d.complete();  // a GL pass may still read the buffers the search and the read-back read
  if (d.check_positions) d.check_finite();
  if (!d.prepared) d.prepare();  // the backend's trees, built on the positions now
  // The candidates' distances, when the backend leaves them to us (GL), are measured on the
  // host from the positions, a GL buffer's read back whole (one copy of vertex_count vertices
  // per mesh) rather than the candidates' own vertices (4 per candidate), since the candidates
  // outnumber the vertices: on the impact scene at contact 100k-160k candidates over 6.4k
  // vertices, 100 KB of positions against 5-8 MB.
  std::vector<std::vector<glm::vec3>> read_back;
  const std::vector<collision::MeshVertices> pose = d.host_vertices(read_back);
  std::vector<float> distances;
  d.make_current();
  const std::vector<collision::ProximityCandidate> found =
      d.backend->find_proximity({.positions = pose.data(),
                                 .motion = motion_of.empty() ? nullptr : motion_of.data(),
                                 .reach = reach_of.data(),
                                 .flat_motion = motion,
                                 .flat_reach = reach,
                                 .mesh_pairs = mesh_pairs},
                                distances);
  // The search's inputs, for widen_proximity(): the pose copied (a host array is read in
  // place and will have moved on).
  Impl::ProximitySearch& last = d.last_proximity;
  last.pose.resize(d.meshes.size());
  for (std::size_t m = 0; m < d.meshes.size(); ++m) {
    last.pose[m].resize(d.meshes[m].vertex_count);
    for (std::uint32_t v = 0; v < d.meshes[m].vertex_count; ++v)
      last.pose[m][v] = collision::vertex_position(pose.data(), static_cast<std::uint32_t>(m), v);
  }
  last.motion.assign(motion.begin(), motion.end());
  last.reach.assign(reach.begin(), reach.end());
  last.mesh_pairs = std::move(mesh_pairs);
  last.valid = true;
  return to_proximity_pairs(d, found, distances, pose);
}

std::vector<ProximityPair> Detector::widen_proximity(std::span<const std::uint32_t> vertices,
                                                     std::span<const float> reach) {
  Impl& d = *impl_;
  Impl::ProximitySearch& last = d.last_proximity;
  if (!last.valid) throw Error("widen_proximity: no find_proximity() to widen yet");
  if (vertices.size() != reach.size()) {
    throw InputError("widen_proximity",
                     "takes one reach per vertex named: " + std::to_string(vertices.size()) +
                         " vertices, " + std::to_string(reach.size()) + " reaches");
  }
  const std::vector<std::uint32_t>& first = d.vertex_first;
  std::vector<std::array<std::uint32_t, 2>> widened(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const std::uint32_t v = vertices[i];
    if (v >= first.back()) {
      throw InputError("widen_proximity", "vertex " + std::to_string(v) + " (entry " +
                                              std::to_string(i) + ") is not below the " +
                                              std::to_string(first.back()) + " vertices");
    }
    if (!(reach[i] >= 0.0f) || !std::isfinite(reach[i])) {
      throw InputError("widen_proximity", "vertex " + std::to_string(v) + " has a reach of " +
                                              std::to_string(reach[i]) +
                                              " (a finite value >= 0 is wanted)");
    }
    const auto mesh = static_cast<std::uint32_t>(std::upper_bound(first.begin(), first.end(), v) -
                                                 first.begin() - 1);
    widened[i] = {mesh, v - first[mesh]};
  }
  for (std::size_t i = 0; i < vertices.size(); ++i)
    last.reach[vertices[i]] = reach[i];
  std::vector<collision::MeshVertices> pose(d.meshes.size());
  std::vector<collision::MeshVertices> motion_of(last.motion.empty() ? 0u : d.meshes.size());
  std::vector<const float*> reach_of(d.meshes.size());
  for (std::size_t m = 0; m < d.meshes.size(); ++m) {
    pose[m] = {&last.pose[m][0].x, 3u};
    if (!motion_of.empty()) motion_of[m] = {&last.motion[first[m]].x, 3u};
    reach_of[m] = last.reach.data() + first[m];
  }
  std::vector<float> distances;
  d.make_current();
  const std::vector<collision::ProximityCandidate> found =
      d.backend->widen_proximity({.positions = pose.data(),
                                  .motion = motion_of.empty() ? nullptr : motion_of.data(),
                                  .reach = reach_of.data(),
                                  .flat_motion = last.motion,
                                  .flat_reach = last.reach,
                                  .mesh_pairs = last.mesh_pairs},
                                 widened, distances);
  return to_proximity_pairs(d, found, distances, pose);
}

CollisionCounts Detector::counts() const {
  if (!impl_->detected) return {};
  impl_->complete();
  const gpu::CollisionCounters c = impl_->backend->counters();
  return {c.face_pairs, c.box_pairs, c.colliding_faces, c.candidates};
}

std::vector<std::uint32_t> Detector::face_flags() const {
  const std::size_t faces = impl_->data.faces.size();
  if (!impl_->detected) return std::vector<std::uint32_t>(faces, 0u);
  impl_->complete();
  std::vector<std::uint32_t> flags;
  impl_->backend->download_face_flags(flags);
  flags.resize(faces);  // a GL buffer holds at least one element
  return flags;
}

std::vector<gpu::Box> Detector::leaf_boxes() const {
  const std::size_t count = impl_->meshes.size() * gpu::kLeafBoxesPerBody;
  if (!impl_->prepared) return std::vector<gpu::Box>(count, gpu::Box{});
  impl_->complete();
  std::vector<gpu::Box> boxes;
  impl_->backend->download_boxes(boxes);
  boxes.resize(count);
  return boxes;
}

std::uint32_t Detector::gl_face_flag_buffer() const {
  return impl_->backend->gl_face_flag_buffer();
}
std::uint32_t Detector::gl_contact_buffer() const {
  return impl_->backend->gl_face_pair_buffer();
}
std::string_view Detector::backend_name() const {
  return impl_->backend->name();
}
std::string Detector::device() const {
  return impl_->backend->device();
}
const std::string& Detector::notice() const {
  return impl_->notice;
}

}  // namespace deformcd
