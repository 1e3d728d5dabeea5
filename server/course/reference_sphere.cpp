#include "course/reference_sphere.h"

namespace shadelab::course {

namespace {
glm::dvec3 rgb(const Course& c, UniformRole role) {
  const PageUniform* u = c.uniform_with_role(role);
  if (!u || u->value.size() < 3) return glm::dvec3(0.0);
  return {u->value[0], u->value[1], u->value[2]};
}
}  // namespace

Expected<reference::PhongSphere> reference_sphere(const Course& c) {
  auto box = fit_bounds(c);
  if (!box) return box.take_error();
  reference::PhongSphere s;
  s.radius = (box->max.y - box->min.y) / 2.0;
  s.center = {(box->min.x + box->max.x) / 2.0, box->min.y + s.radius, (box->min.z + box->max.z) / 2.0};
  s.ambient = rgb(c, UniformRole::ambient);
  s.diffuse = rgb(c, UniformRole::diffuse);
  s.specular = rgb(c, UniformRole::specular);
  s.light = rgb(c, UniformRole::light_position);
  s.light_color = rgb(c, UniformRole::light_color);
  s.specular_alpha = c.specular_exponent();
  s.camera = c.camera;
  return s;
}

}  // namespace shadelab::course
