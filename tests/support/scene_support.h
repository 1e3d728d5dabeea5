#pragma once
// Scene tests share one SceneRenderer on the test binary's EGL context.
#include <nlohmann/json.hpp>

#include "scene/scene_description.h"
#include "scene_render/scene_renderer.h"

namespace shadelab::testkit {

scene_render::SceneRenderer& shared_scene_renderer();
// Parses and renders; a parse or render error fails the calling test through the Expected.
Expected<scene_render::SceneRender> render_scene(const nlohmann::json& scene, bool keep_radiance = false);
// One of assets/scenes/*.json, as compiled into the binary.
nlohmann::json example_scene(const std::string& name);
// Every channel of every pixel finite (and the count of those that are not).
size_t non_finite_values(const image::Image& radiance);
const scene_render::ObjectFraming* framing_of(const scene_render::SceneRender& r, const std::string& name);
bool ran_pass(const scene_render::SceneRender& r, const std::string& name);

}  // namespace shadelab::testkit
