#include "scene_render/depth_convention.h"

namespace shadelab::scene_render {

glm::dmat4 projection(bool perspective, double half_width, double half_height, double near, double far,
                      bool reversed, const DepthConvention& convention) {
  // depth * w = a * z + b, with z the (negative) camera-space z.
  const double range = far - near;
  double a, b;
  if (perspective) {
    a = reversed ? near / range : -far / range;
    b = reversed ? near * far / range : -far * near / range;
  } else {
    a = reversed ? 1 / range : -1 / range;
    b = reversed ? far / range : -near / range;
  }
  const double w_of_z = perspective ? -1 : 0, w_const = perspective ? 0 : 1;
  // z_clip = depth * w in [0, w]; or 2 * depth * w - w in [-w, w].
  double za = a, zb = b;
  if (!convention.zero_to_one) {
    za = 2 * a - w_of_z;
    zb = 2 * b - w_const;
  }
  glm::dmat4 m(0.0);
  m[0][0] = 1 / half_width;
  m[1][1] = 1 / half_height;
  m[2][2] = za;
  m[3][2] = zb;
  m[2][3] = w_of_z;
  m[3][3] = w_const;
  return m;
}

glm::dmat4 camera_projection(const scene::CameraModel& camera, const DepthConvention& convention) {
  return projection(camera.type == scene::Projection::perspective, camera.plane.half_width, camera.plane.half_height,
                    camera.clip_start, camera.clip_end, convention.reversed, convention);
}

glm::dmat4 clip_to_texture(const DepthConvention& convention) {
  glm::dmat4 m(0.0);
  m[0][0] = 0.5;
  m[1][1] = 0.5;
  m[3][0] = 0.5;  // u = 0.5 x + 0.5 w
  m[3][1] = 0.5;
  m[2][2] = convention.zero_to_one ? 1.0 : 0.5;
  m[3][2] = convention.zero_to_one ? 0.0 : 0.5;
  m[3][3] = 1.0;
  return m;
}

}  // namespace shadelab::scene_render
