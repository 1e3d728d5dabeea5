#pragma once
// The accuracy reference: the homework's scene with an analytic sphere in place of the mesh,
// ray-cast in double precision with exact normals, shaded by the same Phong model as the
// course's `specular` reference (ambient + Lambert + Phong, specular only where N.L > 0),
// each sample clamped to [0, 1] as an 8-bit target clamps it, averaged over n x n samples per
// pixel (a box filter, as a multisample resolve is). No GL: it is the thing GL is measured against.
#include <glm/vec3.hpp>

#include "image/image.h"
#include "render/homework_contract.h"

namespace shadelab::reference {

// Every value is a course's (course/reference_sphere.h builds one from a profile).
struct PhongSphere {
  double radius = 0;
  glm::dvec3 center{0.0};  // in mesh space
  glm::dvec3 ambient{0.0}, diffuse{0.0}, specular{0.0};
  glm::dvec3 light{0.0}, light_color{0.0};
  double specular_alpha = 0;
  render::PageCamera camera;
};

// RGBA float image (alpha 1), rows top-down, of frame `degrees` (the sphere is rotation-invariant).
image::Image raycast(const PhongSphere& scene, int width, int height, int samples_per_axis);

// The Phong colour at a world-space surface point with unit normal n, unclamped (exposed for tests).
glm::dvec3 phong(const PhongSphere& scene, const glm::dvec3& p, const glm::dvec3& n);

}  // namespace shadelab::reference
