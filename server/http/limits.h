#pragma once
// What the HTTP edge accepts. Defaults are sized for a 2-core machine serving a class.
#include <cstddef>

#include "render/render_request.h"
#include "scene/scene_description.h"

namespace shadelab::http {

struct Limits {
  render::RenderLimits render;          // width, height <= 2048; frames <= 36; 64 KiB source per stage
  size_t max_body_bytes = 16u << 20;    // 16 MiB
  size_t max_mesh_bytes = 16u << 20;
  size_t max_stored_meshes = 64;
  // Sheets decode their images in the HTTP process (server/http/sheet_routes.cpp): two at once.
  size_t max_concurrent_sheets = 2;
  scene::SceneLimits scene;             // objects <= 64, lights <= 8, width, height <= 4096
};

}  // namespace shadelab::http
