#pragma once
// Projection matrices for the depth convention the context offers. With GL_EXT_clip_control the
// camera uses reversed Z into a float depth buffer (depth 1 at the near plane, 0 at the far one):
// float precision then follows 1/z, and a 1e-6 : 1e6 near/far ratio keeps distinct depths.
// Without it, the usual forward depth in [-1, 1] clip space.
//
// | Matrix            | Depth at near | Depth at far | Test    | Clear |
// |-------------------|---------------|--------------|---------|-------|
// | camera, reversed  | 1             | 0            | GREATER | 0     |
// | camera, forward   | 0             | 1            | LESS    | 1     |
// | shadow views      | 0             | 1            | LESS    | 1     |
#include <glm/mat4x4.hpp>

#include "scene/camera_model.h"

namespace shadelab::scene_render {

struct DepthConvention {
  bool zero_to_one = false;  // clip-space z in [0, w] (EXT_clip_control) instead of [-w, w]
  bool reversed = false;     // the camera's depth runs 1 -> 0 from near to far
};

// `half_width`/`half_height`: tan of the half angles (perspective) or half extents (orthographic).
glm::dmat4 projection(bool perspective, double half_width, double half_height, double near, double far,
                      bool reversed, const DepthConvention& convention);
glm::dmat4 camera_projection(const scene::CameraModel& camera, const DepthConvention& convention);

// Clip space -> (u * w, v * w, depth * w, w) with u, v and depth in [0, 1]: what a shadow lookup
// divides by w and compares.
glm::dmat4 clip_to_texture(const DepthConvention& convention);

}  // namespace shadelab::scene_render
