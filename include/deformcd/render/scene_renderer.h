#pragma once
/// \file scene_renderer.h
/// Draws a World straight from its OpenGL buffers: the node positions (SSBO 0) are the vertex
/// buffer and the collision pass's face flags (SSBO 5) are read by the fragment shaders, so
/// nothing is copied to the CPU per frame. Needs a world on the GL backend and its context
/// current.
///
///     deformcd::render::SceneRenderer renderer(world);
///     deformcd::render::OffscreenTarget target(640, 480);
///     target.bind();
///     renderer.draw(camera, 640, 480);
///     deformcd::render::write_png("frame.png", target.read());

#include <memory>

#include <glm/vec3.hpp>

#include "deformcd/render/camera.h"
#include "deformcd/world.h"

namespace deformcd::render {

/// How SceneRenderer draws the bodies.
enum class RenderMode {
  /// The paper's figures: every surface edge, see-through, in a dark colour per body, with the
  /// colliding faces filled on top: body 0's red (1,0,0), body 1's blue (0,0,1), others green.
  kWireframe,
  /// Lit opaque faces (flat normals), colliding faces in the same colours; the colliding faces
  /// are drawn again on top, so those inside the other body stay visible.
  kShaded,
};

/// What SceneRenderer::draw draws, and in which colours.
struct DrawOptions {
  RenderMode mode = RenderMode::kWireframe;  ///< wireframe (the paper's figures) or shaded
  /// Colour the faces the world's last collision pass flagged. Turn off when no pass ran (the
  /// flags would be stale), e.g. with BroadPhase::kNone.
  bool show_collisions = true;
  glm::vec3 background{1.0f};  ///< clear colour, RGB in [0, 1]
};

/// Draws a GL world straight from its buffers (positions, face flags), with no CPU copy.
class SceneRenderer {
 public:
  /// Compiles the shaders and uploads the index and per-face body buffers once, from
  /// world.faces(). The world must outlive the renderer. Throws GlError when the world is not
  /// on the GL backend, when the device cannot read two shader storage blocks in a fragment
  /// shader, or when a shader does not compile.
  explicit SceneRenderer(const World& world);
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  /// Clears and draws the world's current state into the bound framebuffer, over the viewport
  /// (0, 0, width, height), seen by `camera`. Leaves depth testing as it needs it, polygon
  /// mode GL_FILL, and no program or vertex array bound.
  void draw(const Camera& camera, int width, int height, const DrawOptions& options = {}) const;

 private:
  struct Resources;
  const World* world_;
  std::unique_ptr<Resources> gl_;
};

}  // namespace deformcd::render
