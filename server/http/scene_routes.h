#pragma once
// The headers that carry a scene's report when the body of POST /api/scene is a PNG.
#include <string>

#include "scene_render/scene_report.h"

namespace shadelab::http {

// "shadow;dur=3.20, main;dur=74.10": Server-Timing syntax, one entry per pass that ran.
std::string scene_passes_header(const scene_render::SceneReport& report);
// "Suzanne;fully-visible;in-frame=1.000;coverage=0.1398, Sphere;cropped;in-frame=0.812;coverage=0.0977"
std::string scene_framing_header(const scene_render::SceneReport& report);
// "shadows, ground_reflection" (or "none").
std::string scene_features_header(const scene_render::SceneReport& report);

}  // namespace shadelab::http
