// Fuzz target of the public Detector (CPU backend): random meshes and positions from the input's
// bytes, with indices out of range, repeated and degenerate triangles, and raw float bits for the
// coordinates (NaN, infinities, huge and tiny values, signed zeros). Bad input may only end in an
// InputError naming a mesh (or the pair list); a detector that accepted its input must give, with
// every broad phase, exactly the contacts of brute force, each naming existing triangles, in
// order. Anything else (another exception, a disagreement, a sanitizer report) is a finding.

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <tuple>
#include <vector>

#include "deformcd/detector.h"
#include "deformcd/error.h"
#include "fuzz_support.h"

namespace {

using namespace deformcd;

// The input, read front to back; past its end every read is 0.
class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  float coordinate() {
    // One byte in four picks raw bits (NaN, Inf, denormals, huge); the others a small grid
    // value, so that triangles of different meshes meet often.
    const std::uint8_t kind = byte();
    if (kind % 4 == 0) {
      std::uint32_t bits = 0;
      for (int i = 0; i < 4; ++i)
        bits = (bits << 8) | byte();
      float f = 0.0f;
      std::memcpy(&f, &bits, sizeof f);
      return f;
    }
    return static_cast<float>(static_cast<int>(byte()) - 128) / 32.0f;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

struct FuzzMesh {
  CollisionMesh mesh;
  std::vector<glm::vec3> positions;
};

std::vector<Contact> detect_with(const std::vector<FuzzMesh>& meshes,
                                 const DetectorOptions& options) {
  std::vector<CollisionMesh> m;
  for (const FuzzMesh& f : meshes)
    m.push_back(f.mesh);
  Detector d(m, options);
  for (std::size_t i = 0; i < meshes.size(); ++i)
    d.set_positions(i, std::span<const glm::vec3>(meshes[i].positions));
  d.detect();
  return d.contacts();
}

bool same(const std::vector<Contact>& x, const std::vector<Contact>& y) {
  if (x.size() != y.size()) return false;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const auto key = [](const Contact& c) {
      return std::tie(c.a.body, c.a.face, c.b.body, c.b.face, c.coplanar);
    };
    if (key(x[i]) != key(y[i])) return false;
    for (int e = 0; e < 2; ++e) {  // bit for bit (NaN never appears: inputs are finite)
      if (std::memcmp(&x[i].segment[e], &y[i].segment[e], sizeof(glm::vec3)) != 0) return false;
    }
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  const int mesh_count = 1 + in.byte() % 3;
  std::vector<FuzzMesh> meshes(static_cast<std::size_t>(mesh_count));
  for (FuzzMesh& f : meshes) {
    f.mesh.vertex_count = in.byte() % 24;
    const int triangles = in.byte() % 32;
    f.mesh.self_collision = (in.byte() & 1u) != 0;
    for (int t = 0; t < triangles; ++t) {
      Triangle tri{};
      // Mostly in range; now and then one past the end (an index the detector must reject).
      for (std::uint32_t& v : tri)
        v = in.byte() % (f.mesh.vertex_count + 1 + (in.byte() % 16 == 0 ? 1 : 0));
      f.mesh.triangles.push_back(tri);
    }
    f.positions.resize(f.mesh.vertex_count);
    for (glm::vec3& p : f.positions)
      p = {in.coordinate(), in.coordinate(), in.coordinate()};
  }
  DetectorOptions options{.backend = BackendKind::kCpu, .threads = 1 + in.byte() % 2};
  if (in.byte() % 4 == 0) {  // a pair list, perhaps naming a mesh that does not exist
    options.mesh_pairs = std::vector<MeshPair>{{in.byte() % 4u, in.byte() % 4u}};
  }
  std::vector<Contact> brute;
  try {
    options.broadphase = BroadPhase::kBrute;
    brute = detect_with(meshes, options);
  } catch (const InputError& e) {
    const std::string_view what = e.what();
    if (!what.starts_with("mesh ") && !what.starts_with("mesh pairs")) {
      deformcd::fuzz::finding(std::string("an InputError naming no mesh: ") + e.what());
    }
    if (deformcd::fuzz::verbose()) std::fprintf(stderr, "rejected: %s\n", e.what());
    return 0;
  } catch (const std::exception& e) {
    deformcd::fuzz::finding(std::string("an exception other than InputError: ") + e.what());
  }
  for (std::size_t i = 0; i < brute.size(); ++i) {
    const Contact& c = brute[i];
    if (c.a.body >= meshes.size() || c.b.body >= meshes.size() || c.a.body > c.b.body ||
        c.a.face >= meshes[c.a.body].mesh.triangles.size() ||
        c.b.face >= meshes[c.b.body].mesh.triangles.size() ||
        (c.a.body == c.b.body && c.a.face >= c.b.face) ||
        c.a.nodes != meshes[c.a.body].mesh.triangles[c.a.face]) {
      deformcd::fuzz::finding("contact " + std::to_string(i) + " names no such triangle pair");
    }
  }
  for (BroadPhase method : {BroadPhase::kOctree, BroadPhase::kOctreeCompact, BroadPhase::kBvh}) {
    options.broadphase = method;
    try {
      if (!same(detect_with(meshes, options), brute)) {
        deformcd::fuzz::finding(std::string(broadphase_name(method)) +
                                " found other contacts than brute force");
      }
    } catch (const std::exception& e) {
      deformcd::fuzz::finding(std::string(broadphase_name(method)) + " threw: " + e.what());
    }
  }
  if (deformcd::fuzz::verbose()) std::fprintf(stderr, "%zu contacts\n", brute.size());
  return 0;
}
