#include "scene/scene_description.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "core/json_reader.h"

namespace shadelab::scene {

namespace {

using nlohmann::json;

// The field `key` as one of its table's names ("expected one of ..." recorded for another); the
// fallback when it is absent or wrong.
template <class Enum, std::size_t N>
Enum named(const JsonReader& r, const std::string& key, Enum fallback, const EnumName<Enum> (&table)[N]) {
  std::set<std::string> names;
  for (const auto& row : table) names.insert(std::string(row.name));
  return value_in(table, r.text(key, std::string(name_in(table, fallback)), names)).value_or(fallback);
}

using Reader = JsonReader;

constexpr double kCoordinate = 1e7;  // metres; beyond this a float32 vertex has no precision left

Material read_material(const Reader& r) {
  r.only({"baseColor", "metallic", "roughness", "specular", "subsurface", "subsurfaceColor", "subsurfaceRadius",
          "emission", "emissionStrength", "alpha"});
  Material m;
  m.base_color = r.vec3("baseColor", m.base_color, 0, 1);
  m.metallic = r.number("metallic", m.metallic, 0, 1);
  m.roughness = r.number("roughness", m.roughness, 0, 1);
  m.specular = r.number("specular", m.specular, 0, 1);
  m.subsurface = r.number("subsurface", m.subsurface, 0, 1);
  m.subsurface_color = r.vec3("subsurfaceColor", m.subsurface_color, 0, 1);
  m.subsurface_radius = r.vec3("subsurfaceRadius", m.subsurface_radius, 0, 100);
  m.emission = r.vec3("emission", m.emission, 0, 1);
  m.emission_strength = r.number("emissionStrength", m.emission_strength, 0, 1e6);
  m.alpha = r.number("alpha", m.alpha, 0, 1);
  return m;
}

Material material_at(const Reader& parent, const std::string& key, std::string* error) {
  if (!parent.has(key)) return {};
  return read_material(Reader(parent.get(key), parent.at(key), error));
}

Object read_object(const Reader& r, size_t index, std::string* error) {
  r.only({"name", "mesh", "location", "rotation", "scale", "shading", "material"});
  Object o;
  o.name = r.text("name", "Object." + std::to_string(index));
  // The mesh names what the worker draws: an empty name is no mesh, said here rather than as a
  // lookup of '' that finds nothing.
  const std::string mesh_kinds = "a built-in mesh, an uploaded mesh id or a file field";
  if (!r.has("mesh")) r.fail(r.at("mesh") + ": required (" + mesh_kinds + ")");
  o.mesh = r.text("mesh", "");
  if (o.mesh.empty()) r.fail(r.at("mesh") + ": empty (name " + mesh_kinds + ")");  // the first error stands
  o.location = r.vec3("location", o.location, -kCoordinate, kCoordinate);
  o.rotation_degrees = r.vec3("rotation", o.rotation_degrees, -1e6, 1e6);
  o.scale = r.vec3("scale", o.scale, -1e6, 1e6, true);
  o.shading = named(r, "shading", o.shading, kShadingNames);
  o.material = material_at(r, "material", error);
  return o;
}

Camera read_camera(const Reader& r) {
  r.only({"location", "rotation", "target", "type", "lens", "sensorWidth", "sensorFit", "orthoScale", "clipStart", "clipEnd"});
  Camera c;
  c.location = r.vec3("location", c.location, -kCoordinate, kCoordinate);
  if (r.has("rotation") && r.has("target")) r.fail(r.at("rotation") + ": give rotation or target, not both");
  if (r.has("rotation")) c.rotation_degrees = r.vec3("rotation", {0, 0, 0}, -1e6, 1e6);
  c.target = r.vec3("target", c.target, -kCoordinate, kCoordinate);
  c.type = named(r, "type", c.type, kProjectionNames);
  // Blender's own limits: lens 1 mm and up, sensor 1..100 mm, clip start > 0.
  c.lens_mm = r.number("lens", c.lens_mm, 1, 5000);
  c.sensor_width_mm = r.number("sensorWidth", c.sensor_width_mm, 1, 100);
  c.sensor_fit = named(r, "sensorFit", c.sensor_fit, kSensorFitNames);
  c.ortho_scale = r.number("orthoScale", c.ortho_scale, 1e-6, 1e7);
  c.clip_start = r.number("clipStart", c.clip_start, 1e-6, 1e7);
  c.clip_end = r.number("clipEnd", c.clip_end, 1e-6, 1e9);
  if (c.clip_end <= c.clip_start) r.fail(r.at("clipEnd") + ": must be greater than clipStart");
  return c;
}

Light read_light(const Reader& r, size_t index) {
  r.only({"name", "type", "color", "location", "rotation", "target", "power", "strength", "radius", "angle", "spotSize",
          "spotBlend", "size", "castShadow"});
  Light l;
  l.name = r.text("name", "Light." + std::to_string(index));
  if (!r.has("type")) r.fail(r.at("type") + ": required (point, sun, spot or area)");
  l.type = named(r, "type", l.type, kLightTypeNames);
  l.color = r.vec3("color", l.color, 0, 1e3);
  l.location = r.vec3("location", l.location, -kCoordinate, kCoordinate);
  if (r.has("rotation") && r.has("target")) r.fail(r.at("rotation") + ": give rotation or target, not both");
  if (r.has("rotation")) l.rotation_degrees = r.vec3("rotation", {0, 0, 0}, -1e6, 1e6);
  if (r.has("target")) l.target = r.vec3("target", {0, 0, 0}, -kCoordinate, kCoordinate);
  l.power_w = r.number("power", l.power_w, 0, 1e9);
  l.strength = r.number("strength", l.strength, 0, 1e6);
  l.radius = r.number("radius", l.radius, 0, 1e4);
  l.angle_degrees = r.number("angle", l.angle_degrees, 0, 180);
  l.spot_size_degrees = r.number("spotSize", l.spot_size_degrees, 1, 180);
  l.spot_blend = r.number("spotBlend", l.spot_blend, 0, 1);
  l.size = r.number("size", l.size, 0, 1e4);
  l.cast_shadow = r.boolean("castShadow", l.cast_shadow);
  return l;
}

RenderSettings read_render(const Reader& r, const SceneLimits& limits) {
  r.only({"width", "height", "resolutionPercentage", "engine", "viewTransform", "samples", "shadowMapSize", "shadowFilterTaps",
          "reflectionMapSize", "workbenchShadows", "framing"});
  RenderSettings s;
  s.width = r.integer("width", s.width, 1, limits.max_dimension);
  s.height = r.integer("height", s.height, 1, limits.max_dimension);
  s.percentage = r.integer("resolutionPercentage", s.percentage, 1, 100);
  s.width = std::max(1, s.width * s.percentage / 100);
  s.height = std::max(1, s.height * s.percentage / 100);
  s.engine = named(r, "engine", s.engine, kEngineNames);
  s.view_transform = named(r, "viewTransform", s.view_transform, kViewTransformNames);
  s.samples = r.integer("samples", s.samples, 0, 4);
  if (s.samples == 1 || s.samples == 3) r.fail(r.at("samples") + ": expected 0, 2 or 4");
  s.shadow_map_size = r.integer("shadowMapSize", s.shadow_map_size, 64, 4096);
  if ((s.shadow_map_size & (s.shadow_map_size - 1)) != 0) r.fail(r.at("shadowMapSize") + ": expected a power of two");
  s.shadow_filter_taps = r.integer("shadowFilterTaps", s.shadow_filter_taps, 1, 64);
  s.reflection_map_size = r.integer("reflectionMapSize", s.reflection_map_size, 16, 2048);
  s.workbench_shadows = r.boolean("workbenchShadows", s.workbench_shadows);
  s.framing = r.boolean("framing", s.framing);
  return s;
}

}  // namespace

Expected<SceneDescription> parse_scene(const json& j, const SceneLimits& limits) {
  std::string error;
  Reader root(j, "", &error, "the scene");
  root.only({"objects", "ground", "camera", "lights", "world", "render"});
  SceneDescription scene;

  if (!root.has("objects") || !root.get("objects").is_array() || root.get("objects").empty()) {
    root.fail("objects: expected a non-empty array of objects");
  } else if (root.get("objects").size() > static_cast<size_t>(limits.max_objects)) {
    root.fail("objects: at most " + std::to_string(limits.max_objects) + " objects");
  } else {
    const json& objects = root.get("objects");
    for (size_t i = 0; i < objects.size(); ++i)
      scene.objects.push_back(read_object(Reader(objects[i], "objects[" + std::to_string(i) + "]", &error), i, &error));
  }

  if (root.has("ground")) {
    Reader g(root.get("ground"), "ground", &error);
    g.only({"size", "height", "material"});
    Ground ground;
    ground.size = g.number("size", ground.size, 1e-6, 1e7);
    ground.height = g.number("height", ground.height, -kCoordinate, kCoordinate);
    ground.material = material_at(g, "material", &error);
    scene.ground = ground;
  }
  if (root.has("camera")) scene.camera = read_camera(Reader(root.get("camera"), "camera", &error));

  if (root.has("lights")) {
    const json& lights = root.get("lights");
    if (!lights.is_array()) root.fail("lights: expected an array");
    else if (lights.size() > static_cast<size_t>(limits.max_lights))
      root.fail("lights: at most " + std::to_string(limits.max_lights) + " lights");
    else
      for (size_t i = 0; i < lights.size(); ++i)
        scene.lights.push_back(read_light(Reader(lights[i], "lights[" + std::to_string(i) + "]", &error), i));
  }
  if (root.has("world")) {
    Reader w(root.get("world"), "world", &error);
    w.only({"color", "strength"});
    scene.world.color = w.vec3("color", scene.world.color, 0, 1e3);
    scene.world.strength = w.number("strength", scene.world.strength, 0, 1e6);
  }
  if (root.has("render")) scene.render = read_render(Reader(root.get("render"), "render", &error), limits);

  std::set<std::string> names;
  for (const auto& o : scene.objects)
    if (!names.insert(o.name).second) root.fail("objects: two objects are named '" + o.name + "'");

  if (!error.empty()) return make_error(ErrorCode::invalid_argument, error);
  return scene;
}

}  // namespace shadelab::scene
