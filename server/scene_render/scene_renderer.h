#pragma once
// Renders a scene description (scene/scene_description.h) on the current GL context: the passes
// the scene calls for (scene/pass_plan.h), each timed, then the view transform, then the framing
// report. A worker holds one SceneRenderer next to its homework Renderer; programs, meshes and
// targets stay warm between jobs.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "image/image.h"
#include "scene/camera_model.h"
#include "scene/mesh.h"
#include "scene/scene_description.h"
#include "scene_render/framing.h"

namespace shadelab::scene_render {

struct PassTiming {
  std::string name;
  double ms = 0;
  nlohmann::json detail = nlohmann::json::object();
};

struct SceneReport {
  std::vector<PassTiming> passes;
  std::vector<std::string> features;
  std::vector<ObjectFraming> framing;  // empty when render.framing is false
  scene::CameraModel camera;
  std::string depth;                   // "reversed-z float32" or "forward float32"
  double total_ms = 0;
  nlohmann::json to_json(const scene::SceneDescription& scene) const;
};

struct SceneRender {
  image::Image image;     // RGBA8, display-referred, rows top-down
  image::Image radiance;  // RGBA32F scene-referred radiance before the view transform, when asked for
  SceneReport report;
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

class SceneRenderer {
 public:
  static Expected<SceneRenderer> create();
  SceneRenderer(SceneRenderer&&) noexcept;
  SceneRenderer& operator=(SceneRenderer&&) noexcept;
  ~SceneRenderer();

  Expected<SceneRender> render(const scene::SceneDescription& scene, const MeshResolver& meshes,
                               const SceneRenderOptions& options = {});

 private:
  struct State;
  explicit SceneRenderer(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace shadelab::scene_render
