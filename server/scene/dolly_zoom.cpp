#include "scene/dolly_zoom.h"

#include <glm/geometric.hpp>

namespace shadelab::scene {

std::vector<DollyStop> dolly_zoom(const glm::dvec3& subject, const glm::dvec3& reference_location,
                                  double reference_lens_mm, const std::vector<double>& lenses_mm) {
  const glm::dvec3 offset = reference_location - subject;
  const double reference_distance = glm::length(offset);
  std::vector<DollyStop> stops;
  for (double lens : lenses_mm) {
    DollyStop s;
    s.lens_mm = lens;
    s.distance = reference_distance * lens / reference_lens_mm;
    s.location = reference_distance > 0 ? subject + offset * (s.distance / reference_distance) : reference_location;
    stops.push_back(s);
  }
  return stops;
}

}  // namespace shadelab::scene
