#include "scene_render/shadow_views.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "scene/blender_convention.h"

namespace shadelab::scene_render {

namespace {

std::array<glm::dvec3, 8> corners(const Aabb& b) {
  std::array<glm::dvec3, 8> c;
  for (int i = 0; i < 8; ++i) c[i] = {i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z};
  return c;
}

double radians(double degrees) { return degrees * std::numbers::pi / 180; }

ShadowView perspective_view(int light, const glm::dvec3& from, const glm::dvec3& direction, double tan_half,
                            double light_size, const Aabb& bounds, const DepthConvention& convention) {
  ShadowView v;
  v.light = light;
  v.perspective = true;
  v.light_from_world = glm::inverse(scene::object_matrix(from, scene::look_at_rotation(from, from + direction), glm::dvec3(1)));
  double far = 0;
  for (const auto& c : corners(bounds)) far = std::max(far, glm::length(c - from));
  v.far = std::max(far * 1.01, 1e-3);
  v.near = std::clamp(v.far * 1e-4, 1e-4, 0.05);
  v.half_extent = tan_half;
  v.light_size = light_size;
  v.clip_from_light = projection(true, tan_half, tan_half, v.near, v.far, false, convention);
  return v;
}

}  // namespace

glm::dvec3 light_direction(const scene::Light& light) {
  if (light.target) {
    const glm::dvec3 d = *light.target - light.location;
    const double n = glm::length(d);
    return n > 0 ? d / n : glm::dvec3(0, 0, -1);
  }
  const glm::dmat3 r = light.rotation_degrees ? scene::euler_xyz_degrees(*light.rotation_degrees) : glm::dmat3(1.0);
  return r * glm::dvec3(0, 0, -1);
}

std::vector<ShadowView> shadow_views(const scene::SceneDescription& scene, const std::vector<int>& lights,
                                     const Aabb& bounds, const DepthConvention& convention) {
  std::vector<ShadowView> views;
  if (bounds.empty()) return views;
  for (int index : lights) {
    const scene::Light& light = scene.lights[static_cast<size_t>(index)];
    const glm::dvec3 dir = light_direction(light);
    switch (light.type) {
      case scene::LightType::sun: {
        ShadowView v;
        v.light = index;
        const glm::dvec3 center = 0.5 * (bounds.min + bounds.max);
        const double radius = 0.5 * glm::length(bounds.max - bounds.min) + 1e-6;
        const glm::dvec3 eye = center - dir * (2 * radius);
        v.light_from_world = glm::inverse(scene::object_matrix(eye, scene::look_at_rotation(eye, center), glm::dvec3(1)));
        Aabb in_light;
        for (const auto& c : corners(bounds)) in_light.add(glm::dvec3(v.light_from_world * glm::dvec4(c, 1)));
        // Square texels: one extent for both axes, centred on the bounds.
        const double half = 0.5 * std::max(in_light.max.x - in_light.min.x, in_light.max.y - in_light.min.y) * 1.02 + 1e-6;
        const glm::dvec2 mid = 0.5 * (glm::dvec2(in_light.min) + glm::dvec2(in_light.max));
        v.near = std::max(-in_light.max.z - 0.01 * radius, 1e-4);
        v.far = -in_light.min.z + 0.01 * radius;
        v.half_extent = half;
        v.light_size = 2 * std::tan(radians(light.angle_degrees) / 2);
        glm::dmat4 recentre(1.0);
        recentre[3] = glm::dvec4(-mid.x, -mid.y, 0, 1);
        v.clip_from_light = projection(false, half, half, v.near, v.far, false, convention) * recentre;
        views.push_back(v);
        break;
      }
      case scene::LightType::spot: {
        const double half = std::min(radians(light.spot_size_degrees) / 2 + radians(2), radians(80));
        views.push_back(perspective_view(index, light.location, dir, std::tan(half), 2 * light.radius, bounds, convention));
        break;
      }
      case scene::LightType::area:
        views.push_back(perspective_view(index, light.location, dir, std::tan(radians(80)), light.size, bounds, convention));
        break;
      case scene::LightType::point: {
        const glm::dvec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        // A little over 90 degrees so filter taps near a face's edge stay on the face.
        for (const auto& axis : axes)
          views.push_back(perspective_view(index, light.location, axis, 1.04, 2 * light.radius, bounds, convention));
        break;
      }
    }
  }
  return views;
}

}  // namespace shadelab::scene_render
