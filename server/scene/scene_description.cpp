#include "scene/scene_description.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <set>
#include <string_view>
#include <variant>

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

// A number or a vector a struct of the scene reads as it is, within a range: its key, where it
// goes, the range. Each key is written once, for the read and for the list of keys known.
template <class T>
struct Field {
  std::string_view key;
  std::variant<double T::*, glm::dvec3 T::*> member;
  double lo, hi;
};

template <class T, std::size_t N>
void read_fields(const Reader& r, T& into, const Field<T> (&fields)[N]) {
  for (const auto& f : fields) {
    const std::string key(f.key);
    if (const auto* number = std::get_if<double T::*>(&f.member)) into.*(*number) = r.number(key, into.*(*number), f.lo, f.hi);
    else if (const auto* vector = std::get_if<glm::dvec3 T::*>(&f.member)) into.*(*vector) = r.vec3(key, into.*(*vector), f.lo, f.hi);
  }
}

// The keys of the tables, and those the reader handles itself, as the format knows them.
template <class T, std::size_t... N>
std::set<std::string> keys_of(std::initializer_list<std::string_view> others, const Field<T> (&... tables)[N]) {
  std::set<std::string> keys(others.begin(), others.end());
  (..., [&](const auto& table) {
    for (const auto& f : table) keys.emplace(f.key);
  }(tables));
  return keys;
}

constexpr Field<Material> kMaterialFields[] = {
    {"baseColor", &Material::base_color, 0, 1},
    {"metallic", &Material::metallic, 0, 1},
    {"roughness", &Material::roughness, 0, 1},
    {"specular", &Material::specular, 0, 1},
    {"subsurface", &Material::subsurface, 0, 1},
    {"subsurfaceColor", &Material::subsurface_color, 0, 1},
    {"subsurfaceRadius", &Material::subsurface_radius, 0, 100},
    {"emission", &Material::emission, 0, 1},
    {"emissionStrength", &Material::emission_strength, 0, 1e6},
    {"alpha", &Material::alpha, 0, 1},
};

// Blender's own limits: lens 1 mm and up, sensor 1..100 mm, clip start > 0.
constexpr Field<Camera> kCameraFields[] = {
    {"lens", &Camera::lens_mm, 1, 5000},         {"sensorWidth", &Camera::sensor_width_mm, 1, 100},
    {"orthoScale", &Camera::ortho_scale, 1e-6, 1e7}, {"clipStart", &Camera::clip_start, 1e-6, 1e7},
    {"clipEnd", &Camera::clip_end, 1e-6, 1e9},
};

constexpr Field<Light> kLightPlace[] = {
    {"color", &Light::color, 0, 1e3},
    {"location", &Light::location, -kCoordinate, kCoordinate},
};
constexpr Field<Light> kLightSize[] = {
    {"power", &Light::power_w, 0, 1e9},          {"strength", &Light::strength, 0, 1e6},
    {"radius", &Light::radius, 0, 1e4},          {"angle", &Light::angle_degrees, 0, 180},
    {"spotSize", &Light::spot_size_degrees, 1, 180}, {"spotBlend", &Light::spot_blend, 0, 1},
    {"size", &Light::size, 0, 1e4},
};

constexpr Field<Ground> kGroundFields[] = {
    {"size", &Ground::size, 1e-6, 1e7},
    {"height", &Ground::height, -kCoordinate, kCoordinate},
};
constexpr Field<World> kWorldFields[] = {
    {"color", &World::color, 0, 1e3},
    {"strength", &World::strength, 0, 1e6},
};

Material read_material(const Reader& r) {
  r.only(keys_of({}, kMaterialFields));
  Material m;
  read_fields(r, m, kMaterialFields);
  return m;
}

Material material_at(const Reader& parent, const std::string& key, std::string* error) {
  if (!parent.has(key)) return {};
  return read_material(Reader(parent.get(key), parent.at(key), error));
}

// Where a camera or a light points: Euler angles or a point it looks at, never both.
void read_rotation(const Reader& r, std::optional<glm::dvec3>& rotation) {
  if (r.has("rotation") && r.has("target")) r.fail(r.at("rotation") + ": give rotation or target, not both");
  if (r.has("rotation")) rotation = r.vec3("rotation", {0, 0, 0}, -1e6, 1e6);
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
  r.only(keys_of({"location", "rotation", "target", "type", "sensorFit"}, kCameraFields));
  Camera c;
  c.location = r.vec3("location", c.location, -kCoordinate, kCoordinate);
  read_rotation(r, c.rotation_degrees);
  c.target = r.vec3("target", c.target, -kCoordinate, kCoordinate);
  c.type = named(r, "type", c.type, kProjectionNames);
  c.sensor_fit = named(r, "sensorFit", c.sensor_fit, kSensorFitNames);
  read_fields(r, c, kCameraFields);
  if (c.clip_end <= c.clip_start) r.fail(r.at("clipEnd") + ": must be greater than clipStart");
  return c;
}

Light read_light(const Reader& r, size_t index) {
  r.only(keys_of({"name", "type", "rotation", "target", "castShadow"}, kLightPlace, kLightSize));
  Light l;
  l.name = r.text("name", "Light." + std::to_string(index));
  if (!r.has("type")) r.fail(r.at("type") + ": required (point, sun, spot or area)");
  l.type = named(r, "type", l.type, kLightTypeNames);
  read_fields(r, l, kLightPlace);
  read_rotation(r, l.rotation_degrees);
  if (r.has("target")) l.target = r.vec3("target", {0, 0, 0}, -kCoordinate, kCoordinate);
  read_fields(r, l, kLightSize);
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
    g.only(keys_of({"material"}, kGroundFields));
    Ground ground;
    read_fields(g, ground, kGroundFields);
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
    w.only(keys_of({}, kWorldFields));
    read_fields(w, scene.world, kWorldFields);
  }
  if (root.has("render")) scene.render = read_render(Reader(root.get("render"), "render", &error), limits);

  std::set<std::string> names;
  for (const auto& o : scene.objects)
    if (!names.insert(o.name).second) root.fail("objects: two objects are named '" + o.name + "'");

  if (!error.empty()) return make_error(ErrorCode::invalid_argument, error);
  return scene;
}

}  // namespace shadelab::scene
