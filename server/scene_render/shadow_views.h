#pragma once
// Where each shadow-casting light looks from, fitted to what it can shadow. Pure math in double;
// the renderer draws one depth layer per view.
//
// | Light | Views | Projection                                     | Penumbra from          |
// |-------|-------|------------------------------------------------|------------------------|
// | sun   | 1     | orthographic, fitted to the scene's bounds     | angle: 2 tan(angle/2)  |
// | spot  | 1     | perspective, the cone (half angle <= 80 deg)   | radius: 2 r            |
// | area  | 1     | perspective, 80 deg half angle along -Z        | size                   |
// | point | 6     | perspective, 90 deg cube faces +X -X +Y -Y +Z -Z | radius: 2 r          |
#include <vector>

#include <glm/mat4x4.hpp>

#include "scene/scene_description.h"
#include "scene_render/depth_convention.h"

namespace shadelab::scene_render {

struct Aabb {
  glm::dvec3 min{1e300}, max{-1e300};
  bool empty() const { return min.x > max.x; }
  void add(const glm::dvec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
};

struct ShadowView {
  int light = 0;                    // index into the scene's lights
  glm::dmat4 light_from_world{1.0}; // the view's camera
  glm::dmat4 clip_from_light{1.0};  // its projection (forward depth)
  bool perspective = false;
  double near = 0, far = 1;
  double half_extent = 1;           // orthographic half width, or tan of the half field of view
  double light_size = 0;            // see the table above
};

// The direction a light points (travels) in the world: its local -Z.
glm::dvec3 light_direction(const scene::Light& light);

// Views for `lights` (indices into scene.lights), given the bounds of everything drawn.
std::vector<ShadowView> shadow_views(const scene::SceneDescription& scene, const std::vector<int>& lights,
                                     const Aabb& bounds, const DepthConvention& convention);

}  // namespace shadelab::scene_render
