// scene::parse_scene on the JSON of POST /api/scene, with the service's limits. Invariants: what
// it accepts is within the limits, and crosses the worker wire unchanged (the worker renders the
// scene the HTTP process validated).
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "fuzz_check.h"
#include "http/limits.h"
#include "wire_round_trip.h"

namespace {

void check_within_limits(const shadelab::scene::SceneDescription& s, const shadelab::scene::SceneLimits& limits) {
  FUZZ_CHECK(!s.objects.empty() && s.objects.size() <= static_cast<size_t>(limits.max_objects));
  FUZZ_CHECK(s.lights.size() <= static_cast<size_t>(limits.max_lights));
  FUZZ_CHECK(s.render.width >= 1 && s.render.width <= limits.max_dimension);
  FUZZ_CHECK(s.render.height >= 1 && s.render.height <= limits.max_dimension);
  FUZZ_CHECK(s.render.samples == 0 || s.render.samples == 2 || s.render.samples == 4);
  FUZZ_CHECK(std::isfinite(s.camera.lens_mm) && s.camera.lens_mm > 0);
  FUZZ_CHECK(s.camera.clip_start > 0 && s.camera.clip_end > s.camera.clip_start);
  for (const auto& o : s.objects) {
    FUZZ_CHECK(!o.mesh.empty());
    for (int k = 0; k < 3; ++k) FUZZ_CHECK(std::isfinite(o.location[k]) && std::isfinite(o.scale[k]));
    FUZZ_CHECK(o.material.roughness >= 0 && o.material.roughness <= 1);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  const auto json = nlohmann::json::parse(data, data + size, nullptr, false);
  if (json.is_discarded()) return 0;
  const shadelab::http::Limits limits;
  auto scene = shadelab::scene::parse_scene(json, limits.scene);
  if (!scene) {
    FUZZ_CHECK(!scene.error().message.empty());
    return 0;
  }
  check_within_limits(*scene, limits.scene);
  shadelab::fuzz::check_scene_crosses_the_wire(*scene);
  return 0;
}
