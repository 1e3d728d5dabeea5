#pragma once
// What a scene render reports besides its image: each pass that ran with its time and what it did,
// the features the scene called for, the framing of every object, the camera and depth convention.
// Plain data: worker/result.h is its wire, and the HTTP headers and the CLI read its fields.
#include <string>
#include <variant>
#include <vector>

#include "scene/scene_description.h"
#include "scene_render/framing.h"

namespace shadelab::scene_render {

struct SetupDetail {
  int objects = 0;
};
struct ShadowDetail {
  int views = 0, size = 0, filter_taps = 0;
};
struct ReflectionDetail {
  int size = 0, levels = 0;
};
struct MainDetail {
  int objects = 0;
  bool ground = false;
  int samples = 0;
  std::string shader_variant;
};
struct ViewDetail {
  scene::ViewTransform transform = scene::ViewTransform::standard;
};
struct ReadbackDetail {};
struct FramingDetail {
  int guard_band_renders = 0;
};
using PassDetail = std::variant<SetupDetail, ShadowDetail, ReflectionDetail, MainDetail, ViewDetail, ReadbackDetail, FramingDetail>;

struct PassTiming {
  double ms = 0;
  PassDetail detail;
  std::string_view name() const;  // setup, shadow, reflection, main, view, readback, framing
};

struct CameraSummary {
  double horizontal_fov_degrees = 0, vertical_fov_degrees = 0;
  scene::Projection type = scene::Projection::perspective;
};

struct SceneReport {
  scene::Engine engine = scene::Engine::eevee;
  scene::ViewTransform view_transform = scene::ViewTransform::filmic;
  int width = 0, height = 0;
  std::vector<PassTiming> passes;
  std::vector<std::string> features;
  std::vector<ObjectFraming> framing;  // empty when render.framing is false
  CameraSummary camera;
  std::string depth;                   // "reversed-z float32" or "forward float32"
  double total_ms = 0;

  // The pass of that kind, or null when it did not run.
  template <class Detail>
  const Detail* detail() const {
    for (const auto& p : passes)
      if (const auto* d = std::get_if<Detail>(&p.detail)) return d;
    return nullptr;
  }
};

}  // namespace shadelab::scene_render
