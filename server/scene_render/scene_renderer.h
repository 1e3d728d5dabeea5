#pragma once
// Renders a scene description (scene/scene_description.h) on the current GL context: the passes
// the scene calls for (scene/pass_plan.h), each timed, then the view transform, then the framing
// report. A worker holds one SceneRenderer next to its homework Renderer; programs, meshes and
// targets stay warm between jobs.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/expected.h"
#include "image/image.h"
#include "scene/camera_model.h"
#include "scene/mesh.h"
#include "scene/scene_description.h"
#include "scene_render/framing.h"
#include "scene_render/scene_report.h"

namespace shadelab::scene_render {

struct SceneRender {
  image::Image image;     // RGBA8, display-referred, rows top-down
  image::Image radiance;  // RGBA32F scene-referred radiance before the view transform, when asked for
  SceneReport report;
  scene::CameraModel camera;  // the camera the image was rendered with (projects scene points to pixels)
};

struct SceneRenderOptions {
  bool keep_radiance = false;  // also read back the linear HDR image (tests, accuracy measurements)
};

// Meshes by reference (a built-in name, an upload id, a file path for the CLI), already in the
// Z-up scene space (scene::to_scene_space); the renderer applies the object's shading. Results
// are cached by reference, so a reference must always name the same bytes.
using MeshResolver = std::function<Expected<scene::Mesh>(const std::string& reference)>;
// Built-in scene meshes only.
Expected<scene::Mesh> resolve_builtin_mesh(const std::string& reference);

struct RenderState;  // scene_passes.h

class SceneRenderer {
 public:
  static Expected<SceneRenderer> create();
  SceneRenderer(SceneRenderer&&) noexcept;
  SceneRenderer& operator=(SceneRenderer&&) noexcept;
  ~SceneRenderer();

  Expected<SceneRender> render(const scene::SceneDescription& scene, const MeshResolver& meshes,
                               const SceneRenderOptions& options = {});

 private:
  explicit SceneRenderer(std::unique_ptr<RenderState> state);
  std::unique_ptr<RenderState> state_;
};

}  // namespace shadelab::scene_render
