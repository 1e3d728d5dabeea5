#include "scene_render/framing.h"

#include <algorithm>

namespace shadelab::scene_render {

VertexFraming frame_vertices(const scene::CameraModel& camera, const glm::dmat4& world_from_object, const scene::Mesh& mesh) {
  VertexFraming f;
  f.total = mesh.positions.size();
  const glm::dmat4 camera_from_object = camera.camera_from_world * world_from_object;
  PixelBox box{glm::dvec2(1e300), glm::dvec2(-1e300)};
  for (const auto& p : mesh.positions) {
    const glm::dvec3 c(camera_from_object * glm::dvec4(glm::dvec3(p), 1.0));
    const double depth = -c.z;
    const bool perspective = camera.type == scene::Projection::perspective;
    if (perspective && !(depth > 0)) {
      f.all_inside = false;
      continue;
    }
    ++f.in_front;
    const double x = perspective ? c.x / depth : c.x, y = perspective ? c.y / depth : c.y;
    const glm::dvec2 px((x / camera.plane.half_width + 1) * 0.5 * camera.width,
                        (1 - y / camera.plane.half_height) * 0.5 * camera.height);
    box.min = glm::min(box.min, px);
    box.max = glm::max(box.max, px);
    if (depth < camera.clip_start || depth > camera.clip_end || px.x < 0 || px.y < 0 || px.x > camera.width ||
        px.y > camera.height)
      f.all_inside = false;
  }
  if (f.in_front > 0) f.box = box;
  if (f.total == 0) f.all_inside = false;
  return f;
}

nlohmann::json to_json(const ObjectFraming& f) {
  nlohmann::json j = {{"name", f.name},
                      {"drawn", f.drawn},
                      {"fullyVisible", f.fully_visible},
                      {"fractionInFrame", f.fraction_in_frame},
                      {"imageCoverage", f.image_coverage},
                      {"visiblePixels", f.visible_pixels},
                      {"behindCamera", f.behind_camera},
                      {"partlyBehindCamera", f.partly_behind_camera}};
  if (f.box)
    j["boundingBox"] = {{"x0", f.box->min.x}, {"y0", f.box->min.y}, {"x1", f.box->max.x}, {"y1", f.box->max.y}};
  else
    j["boundingBox"] = nullptr;
  return j;
}

}  // namespace shadelab::scene_render
