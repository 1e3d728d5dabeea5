#pragma once
// The analytic sphere that stands in for a course's mesh in the accuracy reference
// (reference/phong_raycast.h): the default mesh's height as its diameter, standing where the
// mesh stands, lit and seen as the course's page lights and sees it, with its starter's exponent.
#include "core/expected.h"
#include "course/course.h"
#include "reference/phong_raycast.h"

namespace shadelab::course {

Expected<reference::PhongSphere> reference_sphere(const Course& course);

}  // namespace shadelab::course
