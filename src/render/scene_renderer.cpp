#include "deformcd/render/scene_renderer.h"

#include <epoxy/gl.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "deformcd/error.h"
#include "deformcd/gl/ssbo.h"
#include "gpu/gl/gl_check.h"
#include "render/graphics_program.h"
#include "render/render_embedded_shaders.h"

namespace deformcd::render {

namespace {

// A vertex array object reading attribute 0 (vec4) from vertex-buffer binding 0.
class VertexArray {
 public:
  explicit VertexArray(std::uint32_t element_buffer) {
    DEFORMCD_GL_CHECK(glGenVertexArrays(1, &name_));
    DEFORMCD_GL_CHECK(glBindVertexArray(name_));
    DEFORMCD_GL_CHECK(glEnableVertexAttribArray(0));
    DEFORMCD_GL_CHECK(glVertexAttribFormat(0, 4, GL_FLOAT, GL_FALSE, 0));
    DEFORMCD_GL_CHECK(glVertexAttribBinding(0, 0));
    // The element buffer binding is part of the vertex array's state.
    DEFORMCD_GL_CHECK(glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, element_buffer));
    DEFORMCD_GL_CHECK(glBindVertexArray(0));
  }
  ~VertexArray() { glDeleteVertexArrays(1, &name_); }
  VertexArray(const VertexArray&) = delete;
  VertexArray& operator=(const VertexArray&) = delete;

  [[nodiscard]] GLuint name() const { return name_; }

 private:
  GLuint name_ = 0;
};

std::vector<std::uint32_t> triangle_indices(const std::vector<gpu::Face>& faces) {
  std::vector<std::uint32_t> indices;
  indices.reserve(3 * faces.size());
  for (const gpu::Face& f : faces)
    indices.insert(indices.end(), {f.a, f.b, f.c});
  return indices;
}

std::vector<std::uint32_t> face_bodies(const std::vector<gpu::Face>& faces) {
  std::vector<std::uint32_t> bodies;
  bodies.reserve(faces.size());
  for (const gpu::Face& f : faces)
    bodies.push_back(f.body);
  return bodies;
}

// The binding point `program` declares for shader storage block `block`.
GLuint storage_block_binding(const GraphicsProgram& program, const char* block) {
  const GLuint index =
      DEFORMCD_GL_CHECK(glGetProgramResourceIndex(program.name(), GL_SHADER_STORAGE_BLOCK, block));
  if (index == GL_INVALID_INDEX) {
    throw GlError("shaders '" + program.shader_names() + "' have no shader storage block '" +
                  block + "'");
  }
  const GLenum property = GL_BUFFER_BINDING;
  GLint binding = 0;
  DEFORMCD_GL_CHECK(glGetProgramResourceiv(program.name(), GL_SHADER_STORAGE_BLOCK, index, 1,
                                           &property, 1, nullptr, &binding));
  return static_cast<GLuint>(binding);
}

void check_fragment_storage_blocks() {
  GLint blocks = 0;
  DEFORMCD_GL_CHECK(glGetIntegerv(GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS, &blocks));
  if (blocks < 2) {
    throw GlError(
        "the renderer reads the collision flags and the faces' bodies from two "
        "shader storage blocks in its fragment shaders, but this device allows " +
        std::to_string(blocks) + " (GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS)");
  }
}

}  // namespace

struct SceneRenderer::Resources {
  gl::ShaderLibrary library = render_shader_library();
  GraphicsProgram wire{"render/surface.vert", "render/wire.frag", library};
  GraphicsProgram collision{"render/surface.vert", "render/collision.frag", library};
  GraphicsProgram shaded{"render/surface.vert", "render/shaded.frag", library};
  gl::Ssbo<std::uint32_t> indices;
  gl::Ssbo<std::uint32_t> face_body;
  VertexArray vertex_array{indices.name()};
  GLuint flags_binding = storage_block_binding(collision, "CollisionResult");
  GLuint face_body_binding = storage_block_binding(collision, "FaceBody");
  GLsizei index_count = 0;

  explicit Resources(const std::vector<gpu::Face>& faces)
      : indices(std::span<const std::uint32_t>(triangle_indices(faces))),
        face_body(std::span<const std::uint32_t>(face_bodies(faces))),
        index_count(static_cast<GLsizei>(3 * faces.size())) {}
};

SceneRenderer::SceneRenderer(const World& world) : world_(&world) {
  if (world.gl_position_buffer() == 0 || world.gl_face_flag_buffer() == 0) {
    throw GlError(
        "the renderer draws a world from its OpenGL buffers, but this world runs on "
        "the " +
        std::string(world.backend_name()) + " backend (use BackendKind::kGl)");
  }
  if (3 * world.faces().size() > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max())) {
    throw GlError("the renderer cannot draw " + std::to_string(world.faces().size()) +
                  " faces in one call");
  }
  check_fragment_storage_blocks();
  gl_ = std::make_unique<Resources>(world.faces());
}

SceneRenderer::~SceneRenderer() = default;

void SceneRenderer::draw(const Camera& camera, int width, int height,
                         const DrawOptions& options) const {
  if (width <= 0 || height <= 0) return;  // e.g. a minimized window
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const glm::mat4 view = camera.view();
  const glm::mat4 projection = camera.projection(aspect);
  const GLint show = options.show_collisions ? 1 : 0;
  for (GraphicsProgram* program : {&gl_->wire, &gl_->collision, &gl_->shaded}) {
    program->set_uniform("u_view", view);
    program->set_uniform("u_projection", projection);
  }
  gl_->collision.set_uniform("u_show_collisions", show);
  gl_->shaded.set_uniform("u_show_collisions", show);

  // The world's passes end with these barriers already; repeated here so that drawing does not
  // depend on how the positions and flags were last written.
  DEFORMCD_GL_CHECK(
      glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT));
  DEFORMCD_GL_CHECK(glViewport(0, 0, width, height));
  DEFORMCD_GL_CHECK(
      glClearColor(options.background.r, options.background.g, options.background.b, 1.0f));
  DEFORMCD_GL_CHECK(glClearDepth(1.0));
  DEFORMCD_GL_CHECK(glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT));
  DEFORMCD_GL_CHECK(glDisable(GL_CULL_FACE));
  DEFORMCD_GL_CHECK(glDisable(GL_BLEND));
  DEFORMCD_GL_CHECK(glDepthFunc(GL_LESS));

  DEFORMCD_GL_CHECK(glBindVertexArray(gl_->vertex_array.name()));
  DEFORMCD_GL_CHECK(glBindVertexBuffer(0, world_->gl_position_buffer(), 0, sizeof(glm::vec4)));
  DEFORMCD_GL_CHECK(glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl_->flags_binding,
                                     world_->gl_face_flag_buffer()));
  DEFORMCD_GL_CHECK(
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gl_->face_body_binding, gl_->face_body.name()));
  const auto draw_faces = [&](const GraphicsProgram& program) {
    program.use();
    DEFORMCD_GL_CHECK(glDrawElements(GL_TRIANGLES, gl_->index_count, GL_UNSIGNED_INT, nullptr));
  };

  if (options.mode == RenderMode::kWireframe) {
    // See-through edges (no depth test), then the colliding faces over them, depth-tested
    // among themselves so that the nearer of two crossing patches shows.
    DEFORMCD_GL_CHECK(glDisable(GL_DEPTH_TEST));
    DEFORMCD_GL_CHECK(glPolygonMode(GL_FRONT_AND_BACK, GL_LINE));
    draw_faces(gl_->wire);
    DEFORMCD_GL_CHECK(glPolygonMode(GL_FRONT_AND_BACK, GL_FILL));
  } else {
    DEFORMCD_GL_CHECK(glEnable(GL_DEPTH_TEST));
    draw_faces(gl_->shaded);
    // Colliding faces lie inside the other body, mostly hidden by it: draw them again on top.
    DEFORMCD_GL_CHECK(glClear(GL_DEPTH_BUFFER_BIT));
  }
  if (options.show_collisions) {
    DEFORMCD_GL_CHECK(glEnable(GL_DEPTH_TEST));
    draw_faces(gl_->collision);
  }

  DEFORMCD_GL_CHECK(glUseProgram(0));
  DEFORMCD_GL_CHECK(glBindVertexArray(0));
}

}  // namespace deformcd::render
