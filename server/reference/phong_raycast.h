#pragma once
// The accuracy reference: the homework's scene with an analytic sphere in place of the mesh,
// ray-cast in double precision with exact normals, shaded by the same Phong model as the
// `specular` preset (ambient + Lambert + Phong with alpha 0.6, specular only where N.L > 0),
// each sample clamped to [0, 1] as an 8-bit target clamps it, averaged over n x n samples per
// pixel (a box filter, as a multisample resolve is). No GL: it is the thing GL is measured against.
#include <glm/vec3.hpp>

#include "image/image.h"

namespace shadelab::reference {

struct PhongSphere {
  double radius = 1.75;
  glm::dvec3 center{0.0, 1.75, 0.0};   // in mesh space: standing on y = 0, like the built-ins
  glm::dvec3 ambient{0.2, 0.1, 0.1}, diffuse{0.7, 0.5, 0.1}, specular{0.1, 0.4, 0.8};
  glm::dvec3 light{16.0, 8.0, 4.0};
  double specular_alpha = 0.6;
};

// RGBA float image (alpha 1), rows top-down, of frame `degrees` (the sphere is rotation-invariant).
image::Image raycast(const PhongSphere& scene, int width, int height, int samples_per_axis);

// The Phong colour at a world-space surface point with unit normal n, unclamped (exposed for tests).
glm::dvec3 phong(const PhongSphere& scene, const glm::dvec3& p, const glm::dvec3& n);

}  // namespace shadelab::reference
