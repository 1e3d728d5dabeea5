// The setup pass: meshes resolved and pinned, objects placed, the shadow views chosen.
#include "scene/scene_mesh.h"
#include "scene_render/scene_passes.h"

namespace shadelab::scene_render {

namespace {

using scene::SceneDescription;

// Objects and the ground as draw items, with the world bounds of everything drawn.
Status place_objects(RenderState& st, const MeshResolver& resolve, Frame& f) {
  const SceneDescription& scene = f.scene;
  for (int index : f.plan.drawn_objects) {
    const scene::Object& o = scene.objects[static_cast<size_t>(index)];
    auto m = st.mesh(o.mesh, o.shading, resolve);
    if (!m) {
      Error e = m.take_error();
      e.message = "objects[" + std::to_string(index) + "] ('" + o.name + "'): " + e.message;
      return e;
    }
    DrawItem item{index, std::move(*m), scene::object_matrix(o.location, scene::euler_xyz_degrees(o.rotation_degrees), o.scale), &o.material};
    const Aabb& b = item.mesh->bounds;
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 corner{c & 1 ? b.max.x : b.min.x, c & 2 ? b.max.y : b.min.y, c & 4 ? b.max.z : b.min.z};
      f.bounds.add(glm::dvec3(item.world_from_object * glm::dvec4(corner, 1)));
    }
    (o.material.alpha < 1 && scene.render.engine == scene::Engine::eevee ? f.transparent : f.opaque).push_back(std::move(item));
  }
  if (scene.ground) {
    auto plane = st.mesh("plane", scene::Shading::flat, resolve_builtin_mesh);
    if (!plane) return plane.take_error();
    const double half = scene.ground->size / 2;
    f.ground = DrawItem{-1, std::move(*plane), scene::object_matrix({0, 0, scene.ground->height}, glm::dmat3(1.0), {half, half, 1}),
                        &scene.ground->material};
    f.bounds.add({-half, -half, scene.ground->height});
    f.bounds.add({half, half, scene.ground->height});
  }
  return Ok{};
}

// Eevee's shadow-casting lights; Workbench's one shadow light (the first sun, else Blender's
// default Workbench light direction). A light whose views do not all fit in the shader's array
// casts no shadow (a point light needs six).
void choose_shadow_views(const RenderState& st, Frame& f) {
  const SceneDescription& scene = f.scene;
  f.first_view.assign(scene.lights.size(), -1);
  if (!f.plan.shadows) return;
  SceneDescription workbench_scene;
  const SceneDescription* shadow_scene = &scene;
  std::vector<int> shadow_lights = f.plan.shadow_lights;
  if (scene.render.engine == scene::Engine::workbench) {
    scene::Light sun;
    sun.type = scene::LightType::sun;
    sun.target = glm::dvec3(-0.57735, -0.57735, -0.57735);
    sun.location = glm::dvec3(0.0);
    for (const auto& l : scene.lights)
      if (l.type == scene::LightType::sun) {
        sun = l;
        break;
      }
    workbench_scene.lights.push_back(sun);
    shadow_scene = &workbench_scene;
    shadow_lights = {0};
    f.workbench_light = light_direction(sun);
  }
  const std::vector<ShadowView> views = shadow_views(*shadow_scene, shadow_lights, f.bounds, st.convention);
  for (size_t k = 0; k < views.size();) {
    size_t n = 1;
    while (k + n < views.size() && views[k + n].light == views[k].light) ++n;
    if (f.views.size() + n <= static_cast<size_t>(kMaxShadowViews))
      f.views.insert(f.views.end(), views.begin() + static_cast<long>(k), views.begin() + static_cast<long>(k + n));
    k += n;
  }
  if (scene.render.engine == scene::Engine::eevee)
    for (size_t k = f.views.size(); k-- > 0;) f.first_view[static_cast<size_t>(f.views[k].light)] = static_cast<int>(k);
}

}  // namespace

Expected<Frame> setup_pass(RenderState& st, const SceneDescription& scene, const MeshResolver& resolve) {
  Frame f{scene, scene::plan_passes(scene), scene::make_camera(scene.camera, scene.render.width, scene.render.height), {}, {}, {}, {},
          {}, {}, glm::dvec3(0.0), scene.render.shadow_map_size};
  if (auto s = place_objects(st, resolve, f); !s) return s.take_error();
  choose_shadow_views(st, f);
  return f;
}

}  // namespace shadelab::scene_render
