#pragma once
// Response shaping for POST /api/scene: the headers that carry the report when the body is a PNG.
#include <string>

#include <nlohmann/json.hpp>

namespace shadelab::http {

// "shadow;dur=3.2, main;dur=74.1": Server-Timing syntax, one entry per pass that ran.
std::string scene_passes_header(const nlohmann::json& report);
// "Suzanne;fully-visible;in-frame=1.000;coverage=0.1398, Sphere;cropped;in-frame=0.812;coverage=0.0977"
std::string scene_framing_header(const nlohmann::json& report);
// "shadows, ground_reflection" (or "none").
std::string scene_features_header(const nlohmann::json& report);

}  // namespace shadelab::http
