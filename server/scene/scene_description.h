#pragma once
// A scene as POST /api/scene and `shadelab scene` take it: Blender's names, units and axes
// (scene/blender_convention.h). Parsing checks every field and names the one that is wrong
// ("objects[1].material.roughness: expected a number in [0, 1]").
//
// | Field                 | Blender equivalent                       | Default                     |
// |-----------------------|------------------------------------------|-----------------------------|
// | objects[].mesh        | the object's mesh data                   | required                    |
// | objects[].location    | Object > Location (m)                    | [0, 0, 0]                   |
// | objects[].rotation    | Object > Rotation, XYZ Euler (degrees)   | [0, 0, 0]                   |
// | objects[].scale       | Object > Scale (number or [x, y, z])     | 1                           |
// | objects[].shading     | Shade Smooth / Shade Flat                | "smooth"                    |
// | objects[].material    | Principled BSDF inputs                   | Principled defaults         |
// | ground                | a plane at z = height, `size` m wide     | none                        |
// | camera                | camera object + Camera data              | (0,-10,0) looking at origin |
// | lights[]              | light objects + Light data               | none                        |
// | world                 | World > Color x Strength                 | 0.0509 grey, 1              |
// | render                | Render and Output properties             | 1920 x 1080 at 100%, eevee, |
// |                       | (resolutionPercentage: Resolution %)     | filmic (Blender's defaults) |
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "core/enum_names.h"
#include "core/expected.h"
#include "scene/blender_convention.h"

namespace shadelab::scene {

// Principled BSDF, the inputs Eevee honours that this renderer simulates.
struct Material {
  glm::dvec3 base_color{0.8, 0.8, 0.8};
  double metallic = 0, roughness = 0.5, specular = 0.5;
  double subsurface = 0;
  glm::dvec3 subsurface_color{0.8, 0.8, 0.8};
  glm::dvec3 subsurface_radius{1.0, 0.2, 0.1};
  glm::dvec3 emission{0, 0, 0};
  double emission_strength = 1;
  double alpha = 1;

  bool glossy() const { return metallic > 0 || specular > 0; }
};

enum class Shading { smooth, flat };

struct Object {
  std::string name;
  std::string mesh;  // built-in name, uploaded mesh id, or a multipart file's field name
  glm::dvec3 location{0.0}, rotation_degrees{0.0}, scale{1.0};
  Shading shading = Shading::smooth;
  Material material;
};

struct Ground {
  double size = 10;    // edge length of the square plane (m)
  double height = 0;   // z of the plane
  Material material;
};

enum class Projection { perspective, orthographic };

struct Camera {
  glm::dvec3 location{0, -10, 0};
  std::optional<glm::dvec3> rotation_degrees;  // set: Euler XYZ; else `target` is looked at
  glm::dvec3 target{0, 0, 0};
  Projection type = Projection::perspective;
  double lens_mm = 50, sensor_width_mm = 36;
  SensorFit sensor_fit = SensorFit::automatic;
  double ortho_scale = 6;
  double clip_start = 0.1, clip_end = 100;
};

enum class LightType { point, sun, spot, area };

struct Light {
  std::string name;
  LightType type = LightType::point;
  glm::dvec3 color{1, 1, 1};
  glm::dvec3 location{0, 0, 0};
  std::optional<glm::dvec3> rotation_degrees;  // sun / spot / area: where the light points
  std::optional<glm::dvec3> target;
  double power_w = 1000;     // point, spot, area (W)
  double strength = 1;       // sun (W/m^2)
  double radius = 0.1;       // point, spot: soft-shadow size (m)
  double angle_degrees = 0.526;  // sun: angular diameter (Blender's default)
  double spot_size_degrees = 45, spot_blend = 0.15;
  double size = 1;           // area: edge of the square (m)
  bool cast_shadow = true;
};

struct World {
  glm::dvec3 color{0.050876, 0.050876, 0.050876};
  double strength = 1;
};

enum class Engine { workbench, eevee };
enum class ViewTransform { standard, filmic };

struct RenderSettings {
  // What is rendered: Blender's Resolution X and Y scaled by Resolution % (`resolutionPercentage`,
  // the preview knob), as Blender scales them (rounded down, at least 1).
  int width = 1920, height = 1080;
  int percentage = 100;
  Engine engine = Engine::eevee;
  ViewTransform view_transform = ViewTransform::filmic;
  int samples = 4;                // MSAA samples per pixel: 0, 2 or 4
  int shadow_map_size = 2048;     // texels per side of each shadow view
  int shadow_filter_taps = 16;    // PCF taps of the soft-shadow filter (and half as many blocker taps)
  int reflection_map_size = 256;  // texels per side of the ground radiance map
  bool workbench_shadows = false; // Workbench: Lighting > Shadow
  bool framing = true;            // the per-object framing report (one extra pass)
};

struct SceneDescription {
  std::vector<Object> objects;
  std::optional<Ground> ground;
  Camera camera;
  std::vector<Light> lights;
  World world;
  RenderSettings render;
};

struct SceneLimits {
  int max_objects = 64;
  int max_lights = 8;
  int max_dimension = 4096;
};

// Parses and validates; errors are invalid_argument with the field's path in the message.
Expected<SceneDescription> parse_scene(const nlohmann::json& j, const SceneLimits& limits = {});

// Each closed set of a scene's names in one table, in its enum's order: the scene reader, to_string
// and the worker's wire (worker/scene_json.h) read them.
inline constexpr EnumName<Shading> kShadingNames[] = {{Shading::smooth, "smooth"}, {Shading::flat, "flat"}};
inline constexpr EnumName<Projection> kProjectionNames[] = {{Projection::perspective, "perspective"}, {Projection::orthographic, "orthographic"}};
inline constexpr EnumName<SensorFit> kSensorFitNames[] = {
    {SensorFit::automatic, "auto"}, {SensorFit::horizontal, "horizontal"}, {SensorFit::vertical, "vertical"}};
inline constexpr EnumName<LightType> kLightTypeNames[] = {
    {LightType::point, "point"}, {LightType::sun, "sun"}, {LightType::spot, "spot"}, {LightType::area, "area"}};
inline constexpr EnumName<Engine> kEngineNames[] = {{Engine::workbench, "workbench"}, {Engine::eevee, "eevee"}};
inline constexpr EnumName<ViewTransform> kViewTransformNames[] = {{ViewTransform::standard, "standard"}, {ViewTransform::filmic, "filmic"}};

inline std::string_view to_string(Engine e) { return name_in(kEngineNames, e); }
inline std::string_view to_string(ViewTransform v) { return name_in(kViewTransformNames, v); }
inline std::string_view to_string(LightType t) { return name_in(kLightTypeNames, t); }

}  // namespace shadelab::scene
