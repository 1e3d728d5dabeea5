#include "support/scene_support.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "core/embedded_files.h"
#include "support/test_support.h"

namespace shadelab::testkit {

scene_render::SceneRenderer& shared_scene_renderer() {
  shared_renderer();  // the context
  static auto renderer = [] {
    auto r = scene_render::SceneRenderer::create();
    if (!r) throw std::runtime_error(r.error().format());
    return std::move(*r);
  }();
  return renderer;
}

Expected<scene_render::SceneRender> render_scene(const nlohmann::json& j, bool keep_radiance) {
  auto description = scene::parse_scene(j);
  if (!description) return description.take_error();
  return shared_scene_renderer().render(*description, scene_render::resolve_builtin_mesh, {.keep_radiance = keep_radiance});
}

nlohmann::json example_scene(const std::string& name) {
  const auto text = embedded_file("assets/scenes/" + name + ".json");
  if (!text) throw std::runtime_error("no example scene " + name);
  return nlohmann::json::parse(*text);
}

size_t non_finite_values(const image::Image& radiance) {
  size_t bad = 0;
  for (size_t i = 0; i + 4 <= radiance.bytes.size(); i += 4) {
    float v;
    std::memcpy(&v, &radiance.bytes[i], 4);
    if (!std::isfinite(v)) ++bad;
  }
  return bad;
}

const scene_render::ObjectFraming* framing_of(const scene_render::SceneRender& r, const std::string& name) {
  for (const auto& f : r.report.framing)
    if (f.name == name) return &f;
  return nullptr;
}

bool ran_pass(const scene_render::SceneRender& r, const std::string& name) {
  for (const auto& p : r.report.passes)
    if (p.name() == name) return true;
  return false;
}

}  // namespace shadelab::testkit
