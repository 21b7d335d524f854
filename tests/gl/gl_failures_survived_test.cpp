// GL failures survived (issue 16, point 3), through the public Detector and World: each failure
// injected with gl::fault (src/gpu/gl/fault_injection.h) -- an allocation the driver refuses, a
// shader another driver will not compile, a context that cannot be made current -- is a
// GlError naming what failed; no crash; what already existed keeps its last good state; and
// the CPU backend runs in the same process afterwards.

#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "deformcd/detector.h"
#include "deformcd/error.h"
#include "deformcd/world.h"
#include "gl/expect_gl_error.h"
#include "gl/gl_test_context.h"
#include "gpu/gl/fault_injection.h"
#include "support/contact_compare.h"
#include "support/world_fixtures.h"

namespace deformcd {
namespace {

using gl::fault::Kind;
using gl::fault::ScopedFault;

using test::contains;
using test::gl_error_of;

// Two stacks of k large triangles: mesh 0's in the planes z = z_i, mesh 1's in the planes
// y = y_j (both spread over [-1, 1]). Each triangle covers the square [-1, 1]^2 of its plane, so
// every triangle of one stack crosses every triangle of the other its extent reaches: k x k
// contacts when centred, fewer as mesh 1 rises (only the top planes of mesh 0 still reach it).
// With k = 100, 200 faces and 10,000 contacts: past the initial lists (1,024 face pairs, 4,096
// candidates), so that a pass overflows and complete() grows them.
struct Stacks {
  std::vector<CollisionMesh> meshes;
  std::vector<glm::vec3> a, b;

  explicit Stacks(int k) {
    meshes.resize(2);
    for (int i = 0; i < k; ++i) {
      const float t = -1.0f + 2.0f * static_cast<float>(i) / static_cast<float>(k - 1);
      a.insert(a.end(), {{-4, -2, t}, {4, -2, t}, {0, 6, t}});
      b.insert(b.end(), {{-4, t, -2}, {4, t, -2}, {0, t, 6}});
      const auto first = static_cast<std::uint32_t>(3 * i);
      for (CollisionMesh& m : meshes)
        m.triangles.push_back({first, first + 1, first + 2});
    }
    for (CollisionMesh& m : meshes)
      m.vertex_count = static_cast<std::uint32_t>(3 * k);
    meshes[0].name = "z stack";
    meshes[1].name = "y stack";
    base_b_ = b;
  }
  // Mesh 1 raised by `lift` along z (0: centred).
  void lift(float dz) {
    for (std::size_t v = 0; v < b.size(); ++v)
      b[v] = base_b_[v] + glm::vec3(0, 0, dz);
  }
  Detector detector(const DetectorOptions& options) {
    Detector d(meshes, options);
    d.set_positions(0, std::span<const glm::vec3>(a));
    d.set_positions(1, std::span<const glm::vec3>(b));
    return d;
  }

 private:
  std::vector<glm::vec3> base_b_;
};

// Two overlapping boxes of tetrahedra, in contact from the start.
std::vector<BodyInit> two_boxes() {
  BodyInit a, b;
  a.name = "a";
  a.body = build_body(test::tet_grid(2, 2, 2, 0.1));
  b.name = "b";
  b.body = build_body(test::tet_grid(2, 2, 2, 0.1, {0.15, 0.05, 0.03}));
  return {a, b};
}

// The CPU backend, in the same process after a GL failure: a world that steps and collides.
void expect_cpu_world_runs() {
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  World world(two_boxes(), StepSettings{}, options);
  for (int f = 0; f < 5; ++f)
    world.step();
  EXPECT_EQ(world.backend_name(), "cpu");
  EXPECT_GT(world.contacts().size(), 0u);
}

class GlFailuresSurvivedTest : public gl::test_support::GlTest {
 protected:
  DetectorOptions on_gl() { return {.backend = BackendKind::kGl, .gl_context = &context()}; }
  WorldOptions world_on_gl() {
    WorldOptions options;
    options.backend = BackendKind::kGl;
    options.gl_context = &context();
    return options;
  }
};

// --- An allocation the driver refuses (GL_OUT_OF_MEMORY) -------------------------------------

TEST_F(GlFailuresSurvivedTest, AnUploadTheDriverRefusesLeavesTheDetectorsLastContacts) {
  Stacks stacks(20);
  Detector detector = stacks.detector(on_gl());
  detector.detect();
  const std::vector<Contact> last = detector.contacts();
  ASSERT_EQ(last.size(), 400u);
  const std::uint64_t before = gl::fault::operations(Kind::kBufferAllocation);
  detector.prepare();  // builds the hierarchies again and uploads: every buffer anew
  const std::uint64_t per_upload = gl::fault::operations(Kind::kBufferAllocation) - before;
  ASSERT_GT(per_upload, 0u);
  detector.detect();
  for (std::uint64_t n = 1; n <= per_upload; ++n) {
    std::string message;
    {
      ScopedFault oom(Kind::kBufferAllocation, n);
      message = gl_error_of([&] { detector.prepare(); });
    }
    EXPECT_TRUE(contains(message, "GL collision: allocating ")) << message;
    EXPECT_TRUE(contains(message, "GL_OUT_OF_MEMORY")) << message;
    EXPECT_EQ(test::contacts_difference(detector.contacts(), last), "") << "allocation " << n;
    EXPECT_EQ(detector.counts().contacts, last.size());
  }
  detector.detect();
  EXPECT_EQ(test::contacts_difference(detector.contacts(), last), "");
  Detector cpu = stacks.detector({.backend = BackendKind::kCpu});
  cpu.detect();
  EXPECT_EQ(test::contacts_difference(cpu.contacts(), last), "");
}

// A pass of 10,000 contacts overflows the initial lists; the driver refuses the grown one. That
// pass is lost (it overwrote the last results on the GPU, and its own lists are partial): the
// Detector says so rather than return a truncated list, keeps its buffers, and the next
// detect() grows them and finds every contact, as the CPU backend does.
TEST_F(GlFailuresSurvivedTest, AListThatCannotGrowLosesOnlyThatPass) {
  Stacks stacks(100);
  Detector detector = stacks.detector(on_gl());
  stacks.lift(2.95f);
  detector.detect();
  const std::vector<Contact> few = detector.contacts();
  ASSERT_EQ(few.size(), 300u);  // mesh 0's top 3 planes reach mesh 1
  stacks.lift(0.0f);
  detector.detect();
  std::string message;
  {
    ScopedFault oom(Kind::kBufferAllocation);
    message = gl_error_of([&] { (void)detector.contacts(); });
  }
  EXPECT_TRUE(contains(message,
                       "GL collision: allocating Candidate Pair (SSBO 28), 120000 bytes "
                       "(15000 x 8), failed: glBufferData of 120000 bytes failed: "
                       "GL_OUT_OF_MEMORY"))
      << message;
  EXPECT_TRUE(contains(message, "growing it from 4096 entries after a pass found 10000"))
      << message;
  const std::string lost = gl_error_of([&] { (void)detector.contacts(); });
  EXPECT_TRUE(contains(lost,
                       "the last pass's results are lost (GL collision: allocating "
                       "Candidate Pair (SSBO 28)"))
      << lost;
  EXPECT_THROW((void)detector.counts(), GlError);
  EXPECT_THROW((void)detector.face_flags(), GlError);

  detector.detect();
  const std::vector<Contact> all = detector.contacts();
  EXPECT_EQ(all.size(), 10000u);
  Detector cpu = stacks.detector({.backend = BackendKind::kCpu});
  cpu.detect();
  EXPECT_EQ(test::contacts_difference(all, cpu.contacts()), "");
  stacks.lift(2.95f);
  detector.detect();
  EXPECT_EQ(test::contacts_difference(detector.contacts(), few), "");
}

// Each GL allocation of a World's construction in turn is refused (the simulation's buffers,
// then the detector's): a GlError naming the buffer, and nothing left behind: every buffer name
// GL handed out since (Mesa counts up) names no buffer any more.
TEST_F(GlFailuresSurvivedTest, AWorldWhoseAllocationFailsAtConstructionThrowsCleanly) {
  const std::vector<BodyInit> bodies = two_boxes();
  const auto next_name = [] {
    GLuint name = 0;
    glGenBuffers(1, &name);
    glDeleteBuffers(1, &name);
    return name;
  };
  const GLuint first = next_name();
  const auto live_buffers = [&] {
    int live = 0;
    for (GLuint name = first, end = next_name(); name < end; ++name)
      live += glIsBuffer(name) == GL_TRUE ? 1 : 0;
    return live;
  };
  const std::uint64_t before = gl::fault::operations(Kind::kBufferAllocation);
  std::vector<Contact> expected;
  {
    World world(bodies, StepSettings{}, world_on_gl());
    world.step();
    expected = world.contacts();
    EXPECT_GT(live_buffers(), 30);  // the check sees a World's buffers
  }
  ASSERT_GT(expected.size(), 0u);
  EXPECT_EQ(live_buffers(), 0) << "a World's destruction left buffers behind";
  const std::uint64_t per_world = gl::fault::operations(Kind::kBufferAllocation) - before;
  ASSERT_GE(per_world, 13u + 20u);  // the simulation's buffers and the detector's
  for (std::uint64_t n = 1; n <= per_world; ++n) {
    std::string message;
    {
      ScopedFault oom(Kind::kBufferAllocation, n);
      message = gl_error_of([&] {
        World world(bodies, StepSettings{}, world_on_gl());
        world.step();  // the first pass allocates too (none with the positions read in place)
      });
    }
    if (n == 1) {
      EXPECT_EQ(message.rfind("GL simulation: allocating Node Position (SSBO 0), " +
                                  std::to_string(16 * 2 * 27) + " bytes (54 x 16), failed: ",
                              0),
                0u)
          << message;
    }
    EXPECT_TRUE(contains(message, ": allocating ")) << message;
    EXPECT_TRUE(contains(message, "GL_OUT_OF_MEMORY")) << message;
    EXPECT_EQ(live_buffers(), 0) << "allocation " << n << " left buffers behind";
  }
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  World world(bodies, StepSettings{}, world_on_gl());
  world.step();
  EXPECT_EQ(test::contacts_difference(world.contacts(), expected), "");
  expect_cpu_world_runs();
}

// --- A shader the driver will not compile --------------------------------------------------

// Every shader of a World in turn fails to compile, with the driver's own log: the GlError
// names the shader and maps the driver's line to its file.
TEST_F(GlFailuresSurvivedTest, EachShaderThatFailsToCompileIsNamedWithTheDriversLog) {
  const std::vector<BodyInit> bodies = two_boxes();
  const std::uint64_t before = gl::fault::operations(Kind::kShaderCompile);
  { World world(bodies, StepSettings{}, world_on_gl()); }
  const std::uint64_t per_world = gl::fault::operations(Kind::kShaderCompile) - before;
  ASSERT_GE(per_world, 4u + 12u);  // the simulation's shaders and the detector's
  std::set<std::string> named;
  for (std::uint64_t n = 1; n <= per_world; ++n) {
    std::string message;
    {
      ScopedFault broken(Kind::kShaderCompile, n);
      message = gl_error_of([&] { World world(bodies, StepSettings{}, world_on_gl()); });
    }
    ASSERT_EQ(message.rfind("compiling compute shader '", 0), 0u) << message;
    const std::size_t end = message.find('\'', 26);
    const std::string shader = message.substr(26, end - 26);
    named.insert(shader);
    EXPECT_TRUE(contains(message, "' failed:\n" + shader + ":")) << message;  // file:line
    EXPECT_TRUE(contains(message, "compile_failure_injected_by_gl_fault")) << message;
  }
  EXPECT_EQ(named.size(), per_world) << "each compile names another shader";
  EXPECT_TRUE(named.contains("sim/node_update.comp"));
  EXPECT_TRUE(named.contains("collision/bvh_traverse.comp"));
  expect_cpu_world_runs();
  World world(bodies, StepSettings{}, world_on_gl());  // and GL again, once the driver obliges
  world.step();
  EXPECT_GT(world.contacts().size(), 0u);
}

// --- A context that cannot be made current --------------------------------------------------

TEST_F(GlFailuresSurvivedTest, AContextThatCannotBeMadeCurrentLeavesTheLastContacts) {
  Stacks stacks(20);
  Detector detector = stacks.detector(on_gl());
  detector.detect();
  const std::vector<Contact> last = detector.contacts();
  ASSERT_EQ(last.size(), 400u);
  stacks.lift(2.95f);  // the next pass would find fewer
  std::string message;
  {
    ScopedFault not_current(Kind::kMakeCurrent);
    message = gl_error_of([&] { detector.detect(); });
  }
  EXPECT_EQ(
      message.rfind(
          "making the " + std::string(context().platform_name()) + " context current failed (", 0),
      0u)
      << message;
  EXPECT_TRUE(contains(message, "eglMakeCurrent: EGL_BAD_ACCESS")) << message;
  EXPECT_EQ(test::contacts_difference(detector.contacts(), last), "");

  // A pass queued, then completing it fails: it completes at the next read.
  detector.detect();
  {
    ScopedFault not_current(Kind::kMakeCurrent);
    EXPECT_THROW((void)detector.contacts(), GlError);
  }
  const std::vector<Contact> fewer = detector.contacts();
  EXPECT_EQ(fewer.size(), 20u);  // mesh 0's top plane reaches mesh 1
  Detector cpu = stacks.detector({.backend = BackendKind::kCpu});
  cpu.detect();
  EXPECT_EQ(test::contacts_difference(cpu.contacts(), fewer), "");
}

// A destructor cannot throw: a detector whose context cannot be made current any more is
// destroyed without a crash (leaving its GL objects to their context).
TEST_F(GlFailuresSurvivedTest, ADetectorWhoseContextCannotBeMadeCurrentIsDestroyedSafely) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "the detector's backend is left allocated on purpose: LeakSanitizer reports it";
#else
  Stacks stacks(4);
  auto detector = std::make_unique<Detector>(stacks.detector(on_gl()));
  detector->detect();
  EXPECT_EQ(detector->contacts().size(), 16u);
  {
    ScopedFault not_current(Kind::kMakeCurrent, 1, gl::fault::kForever);
    detector.reset();
  }
  expect_cpu_world_runs();
#endif
}

// No context can be made current at all: kGl is a GlError naming every platform tried, kAuto
// falls back to the CPU and says why.
TEST_F(GlFailuresSurvivedTest, NoContextThatCanBeMadeCurrentMeansTheCpuForAuto) {
  Stacks stacks(4);
  std::string message;
  std::string notice;
  std::string backend;
  {
    ScopedFault not_current(Kind::kMakeCurrent, 1, gl::fault::kForever);
    message = gl_error_of([&] { Detector d(stacks.meshes, {.backend = BackendKind::kGl}); });
    Detector automatic(stacks.meshes, {.backend = BackendKind::kAuto});
    notice = automatic.notice();
    backend = automatic.backend_name();
  }
  EXPECT_TRUE(contains(message, "context current failed")) << message;
  EXPECT_TRUE(contains(message, "injected by gl::fault")) << message;
  EXPECT_EQ(backend, "cpu");
  EXPECT_TRUE(contains(notice, "OpenGL 4.3 is not available, using the CPU backend")) << notice;
  EXPECT_TRUE(contains(notice, "context current failed")) << notice;
  Detector cpu = stacks.detector({.backend = BackendKind::kCpu});
  cpu.detect();
  EXPECT_EQ(cpu.contacts().size(), 16u);
}

}  // namespace
}  // namespace deformcd
