#pragma once
// The homework's quantities a checkpoint's lights cannot see: a colour whose value leaves the
// image as it would be without it (white for a factor, black for the ambient term) under the
// page's light and every probe light, so a shader that leaves it out passes. The page's light is
// white, so without a coloured probe a specular term missing uLightColor is right under every
// light the grader draws. `shadelab course check` warns of each.
#include <string>
#include <vector>

#include "course/course.h"

namespace shadelab::course {

struct UnseenRole {
  std::string checkpoint;
  UniformRole role;
  std::string why;  // "uLightColor is (1, 1, 1), white, under the page's light and every probe: ..."
};

// For each checkpoint, each role its reference reads (by any of the role's names) that no light shows.
std::vector<UnseenRole> unseen_roles(const Course& course);

}  // namespace shadelab::course
