#pragma once
// The dolly zoom (the handout's "vertigo effect"): change the lens and move the camera along its
// line of sight so the subject keeps its size in the image. For a subject at distance d seen
// through a lens of focal length f, its image size goes as f / d, so d' = d * f' / f.
#include <vector>

#include <glm/vec3.hpp>

namespace shadelab::scene {

struct DollyStop {
  double lens_mm = 0;
  double distance = 0;        // from the subject, along the reference line of sight
  glm::dvec3 location{0.0};   // camera location that keeps the subject's size
};

// `reference_location` looks at `subject` through `reference_lens_mm`; one stop per lens.
std::vector<DollyStop> dolly_zoom(const glm::dvec3& subject, const glm::dvec3& reference_location,
                                  double reference_lens_mm, const std::vector<double>& lenses_mm);

}  // namespace shadelab::scene
