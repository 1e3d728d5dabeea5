#pragma once
// A UV sphere with exact (analytic) normals, for accuracy measurements against a ray-cast reference.
#include <glm/vec3.hpp>

#include "scene/mesh.h"

namespace shadelab::scene {

// `segments` around the equator, segments / 2 from pole to pole; 2 triangles per quad.
Mesh uv_sphere(double radius, glm::dvec3 center, int segments);

}  // namespace shadelab::scene
