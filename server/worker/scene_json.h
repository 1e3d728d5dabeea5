#pragma once
// The scene description's JSON form, on the wire and in a scene report: each struct's fields under
// their C++ names, each enum under its scene-file name. It is read only from a trusted sender that
// validated the scene (scene::parse_scene), so it is not re-validated.
#include <optional>
#include <string>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "core/json_fields.h"
#include "scene/scene_description.h"

namespace nlohmann {
template <>
struct adl_serializer<glm::dvec2> {
  static void to_json(json& j, const glm::dvec2& v) { j = {v.x, v.y}; }
  static void from_json(const json& j, glm::dvec2& v) { v = {j.at(0).get<double>(), j.at(1).get<double>()}; }
};
template <>
struct adl_serializer<glm::dvec3> {
  static void to_json(json& j, const glm::dvec3& v) { j = {v.x, v.y, v.z}; }
  static void from_json(const json& j, glm::dvec3& v) { v = {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }
};
// Optional vectors (a camera's or light's rotation, a light's target): null when unset.
template <>
struct adl_serializer<std::optional<glm::dvec3>> {
  static void to_json(json& j, const std::optional<glm::dvec3>& v) { j = v ? json(*v) : json(nullptr); }
  static void from_json(const json& j, std::optional<glm::dvec3>& v) {
    v = j.is_null() ? std::nullopt : std::optional<glm::dvec3>(j.get<glm::dvec3>());
  }
};
}  // namespace nlohmann

namespace shadelab::scene {

// The scene's enums by their names in scene/scene_description.h's tables; a name this build does
// not know is malformed (nlohmann's NLOHMANN_JSON_SERIALIZE_ENUM would read it as the first value).
#define SHADELAB_SCENE_ENUM_JSON(Enum, table)                                                              \
  inline void to_json(nlohmann::json& j, Enum value) { j = std::string(name_in(table, value)); }          \
  inline void from_json(const nlohmann::json& j, Enum& value) { json_fields::Names{table}.read(j, value); }
SHADELAB_SCENE_ENUM_JSON(Shading, kShadingNames)
SHADELAB_SCENE_ENUM_JSON(Projection, kProjectionNames)
SHADELAB_SCENE_ENUM_JSON(SensorFit, kSensorFitNames)
SHADELAB_SCENE_ENUM_JSON(LightType, kLightTypeNames)
SHADELAB_SCENE_ENUM_JSON(Engine, kEngineNames)
SHADELAB_SCENE_ENUM_JSON(ViewTransform, kViewTransformNames)
#undef SHADELAB_SCENE_ENUM_JSON

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Material, base_color, metallic, roughness, specular, subsurface, subsurface_color,
                                   subsurface_radius, emission, emission_strength, alpha)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Object, name, mesh, location, rotation_degrees, scale, shading, material)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Ground, size, height, material)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(World, color, strength)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(RenderSettings, width, height, percentage, engine, view_transform, samples, shadow_map_size,
                                   shadow_filter_taps, reflection_map_size, workbench_shadows, framing)

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Camera, location, rotation_degrees, target, type, lens_mm, sensor_width_mm, sensor_fit,
                                   ortho_scale, clip_start, clip_end)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Light, name, type, color, location, rotation_degrees, target, power_w, strength, radius,
                                   angle_degrees, spot_size_degrees, spot_blend, size, cast_shadow)

}  // namespace shadelab::scene
