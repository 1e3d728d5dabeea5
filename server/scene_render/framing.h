#pragma once
// The checklist asks that both objects be fully in the image. Per object:
//
// | Field              | Meaning                                                                    |
// |--------------------|----------------------------------------------------------------------------|
// | boundingBox        | pixel box of the projected vertices in front of the camera (x right, y    |
// |                    | down, may extend past the image); null when none is in front               |
// | fullyVisible       | every vertex in front of the camera, within the clip range, in the image   |
// | fractionInFrame    | share of the object's projected area inside the frame (1 when fully       |
// |                    | visible; else measured by a guard-band render of the object alone)        |
// | imageCoverage      | share of the image's pixels where the object is the nearest surface        |
// | behindCamera       | no vertex in front of the camera                                           |
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "scene/camera_model.h"
#include "scene/mesh.h"

namespace shadelab::scene_render {

struct PixelBox {
  glm::dvec2 min{0.0}, max{0.0};
};

struct ObjectFraming {
  std::string name;
  bool drawn = true;  // false for a zero-scale object
  std::optional<PixelBox> box;
  bool fully_visible = false;
  bool behind_camera = false;
  bool partly_behind_camera = false;
  double fraction_in_frame = 0;
  double image_coverage = 0;
  long long visible_pixels = 0;
};

// What the vertices alone tell: the box, and whether a guard-band render is needed at all.
struct VertexFraming {
  std::optional<PixelBox> box;
  size_t in_front = 0, total = 0;
  bool all_inside = true;  // every vertex in front, in the clip range, inside the image
};
VertexFraming frame_vertices(const scene::CameraModel& camera, const glm::dmat4& world_from_object, const scene::Mesh& mesh);

}  // namespace shadelab::scene_render
