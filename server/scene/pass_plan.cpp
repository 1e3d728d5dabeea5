#include "scene/pass_plan.h"

#include <cmath>

namespace shadelab::scene {

namespace {

bool zero_scale(const Object& o) { return o.scale.x == 0 || o.scale.y == 0 || o.scale.z == 0; }

double light_output(const Light& l) {
  const double c = l.color.r + l.color.g + l.color.b;
  return c * (l.type == LightType::sun ? l.strength : l.power_w);
}

bool emits(const Material& m) { return m.emission_strength * (m.emission.r + m.emission.g + m.emission.b) > 0; }

}  // namespace

bool is_glossy(const Material& m) { return m.metallic > 0 || (m.specular > 0 && m.roughness < 0.5); }

PassPlan plan_passes(const SceneDescription& scene) {
  PassPlan plan;
  for (size_t i = 0; i < scene.objects.size(); ++i)
    if (!zero_scale(scene.objects[i])) plan.drawn_objects.push_back(static_cast<int>(i));
  const bool anything = !plan.drawn_objects.empty();
  plan.framing = scene.render.framing;

  if (scene.render.engine == Engine::workbench) {
    plan.shadows = scene.render.workbench_shadows && anything;
    return plan;
  }

  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (scene.lights[i].cast_shadow && light_output(scene.lights[i]) > 0 && anything)
      plan.shadow_lights.push_back(static_cast<int>(i));
  plan.shadows = !plan.shadow_lights.empty();

  const auto any_object = [&](auto&& predicate) {
    for (int i : plan.drawn_objects)
      if (predicate(scene.objects[static_cast<size_t>(i)].material)) return true;
    return false;
  };
  plan.reflection = scene.ground && any_object(is_glossy);
  plan.transparency = any_object([](const Material& m) { return m.alpha < 1; });
  const auto ground_has = [&](auto&& predicate) { return scene.ground && predicate(scene.ground->material); };
  const auto sss = [](const Material& m) { return m.subsurface > 0; };
  plan.subsurface = any_object(sss) || ground_has(sss);
  plan.emission = any_object(emits) || ground_has(emits);
  return plan;
}

std::vector<std::string> PassPlan::features() const {
  std::vector<std::string> f;
  if (shadows) f.push_back("shadows");
  if (reflection) f.push_back("ground_reflection");
  if (subsurface) f.push_back("subsurface");
  if (emission) f.push_back("emission");
  if (transparency) f.push_back("transparency");
  return f;
}

}  // namespace shadelab::scene
