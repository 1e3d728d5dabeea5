#include "worker/job.h"

#include <algorithm>
#include <iterator>
#include <optional>

#include <glm/vec3.hpp>

// The scene description's wire form: each struct's fields under their C++ names. It is read only
// from a trusted sender that validated the scene (scene::parse_scene), so it is not re-validated.
namespace nlohmann {
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

NLOHMANN_JSON_SERIALIZE_ENUM(Shading, {{Shading::smooth, "smooth"}, {Shading::flat, "flat"}})
NLOHMANN_JSON_SERIALIZE_ENUM(Projection, {{Projection::perspective, "perspective"}, {Projection::orthographic, "orthographic"}})
NLOHMANN_JSON_SERIALIZE_ENUM(SensorFit, {{SensorFit::automatic, "auto"}, {SensorFit::horizontal, "horizontal"}, {SensorFit::vertical, "vertical"}})
NLOHMANN_JSON_SERIALIZE_ENUM(LightType, {{LightType::point, "point"}, {LightType::sun, "sun"}, {LightType::spot, "spot"}, {LightType::area, "area"}})
NLOHMANN_JSON_SERIALIZE_ENUM(Engine, {{Engine::workbench, "workbench"}, {Engine::eevee, "eevee"}})
NLOHMANN_JSON_SERIALIZE_ENUM(ViewTransform, {{ViewTransform::standard, "standard"}, {ViewTransform::filmic, "filmic"}})

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

namespace shadelab::worker {

using nlohmann::json;

namespace {

constexpr JobKind kKinds[] = {JobKind::render, JobKind::compile, JobKind::mesh_check, JobKind::grade, JobKind::grade_frames, JobKind::scene};

json file_json(const shader::ShaderFile& f) { return {{"name", f.name}, {"text", f.text}}; }
shader::ShaderFile file_from(const json& j) { return {j.at("name"), j.at("text")}; }

json shared_store_json(const store::SharedStoreConfig& s) {
  return {{"url", s.url}, {"timeoutMs", s.timeout.count()}, {"retryAfterMs", s.retry_after.count()},
          {"timeToLiveS", s.time_to_live.count()}, {"maxValueBytes", s.max_value_bytes}};
}

store::SharedStoreConfig shared_store_from(const json& j) {
  store::SharedStoreConfig s;
  s.url = j.at("url");
  s.timeout = std::chrono::milliseconds(j.at("timeoutMs").get<long long>());
  s.retry_after = std::chrono::milliseconds(j.at("retryAfterMs").get<long long>());
  s.time_to_live = std::chrono::seconds(j.at("timeToLiveS").get<long long>());
  s.max_value_bytes = j.at("maxValueBytes");
  return s;
}

// grade::HeatMap's values on the wire, in its order.
constexpr std::string_view heatmap_names[] = {"always", "whenFailing", "never"};

json grade_json(const grade::GradeSpec& g) {
  json mistakes = json::array(), probes = json::array();
  for (const auto& m : g.mistakes)
    mistakes.push_back({{"id", m.id}, {"message", m.message}, {"vertex", file_json(m.vertex)}, {"fragment", file_json(m.fragment)}});
  for (const auto& p : g.probes) probes.push_back({{"name", p.name}, {"lightPosition", p.light_position}, {"checks", p.checks}});
  json constants = json::array();
  for (const auto& k : g.starter_constants) constants.push_back({{"variable", k.variable}, {"meaning", k.meaning}, {"value", k.value}});
  const auto& o = g.options;
  return {{"referenceName", g.reference_name}, {"referenceVertex", file_json(g.reference_vertex)},
          {"referenceFragment", file_json(g.reference_fragment)}, {"mistakes", mistakes}, {"probes", probes},
          {"lightPositionUniforms", g.light_position_uniforms}, {"starterConstants", constants},
          {"referenceStore", g.reference_store.folder}, {"sharedStore", shared_store_json(g.reference_store.shared)},
          {"threshold", o.compare.threshold}, {"spatialTolerance", o.compare.spatial_tolerance},
          {"maxFailingFraction", o.max_failing_fraction}, {"maxScore", o.max_score}, {"sameOutline", o.same_outline},
          {"savedFramesCloserThanReference", o.saved_frames_closer_than_reference}, {"heatmap", heatmap_names[static_cast<int>(g.heatmap)]},
          {"framesFromPage", g.frames_from_page}};
}

grade::GradeSpec grade_from(const json& g) {
  grade::GradeSpec spec;
  spec.reference_name = g.at("referenceName");
  spec.reference_vertex = file_from(g.at("referenceVertex"));
  spec.reference_fragment = file_from(g.at("referenceFragment"));
  for (const auto& m : g.at("mistakes"))
    spec.mistakes.push_back({m.at("id"), m.at("message"), file_from(m.at("vertex")), file_from(m.at("fragment"))});
  for (const auto& p : g.at("probes")) spec.probes.push_back({p.at("name"), p.at("lightPosition").get<std::array<float, 3>>(), p.value("checks", "")});
  spec.light_position_uniforms = g.at("lightPositionUniforms").get<std::vector<std::string>>();
  spec.reference_store = {g.at("referenceStore"), shared_store_from(g.at("sharedStore"))};
  for (const auto& k : g.at("starterConstants")) spec.starter_constants.push_back({k.at("variable"), k.at("meaning"), k.at("value")});
  spec.options.compare.threshold = g.at("threshold");
  spec.options.compare.spatial_tolerance = g.at("spatialTolerance");
  spec.options.max_failing_fraction = g.at("maxFailingFraction");
  spec.options.max_score = g.at("maxScore");
  spec.options.same_outline = g.at("sameOutline");
  spec.options.saved_frames_closer_than_reference = g.at("savedFramesCloserThanReference");
  const auto* named = std::find(std::begin(heatmap_names), std::end(heatmap_names), g.at("heatmap").get<std::string>());
  if (named == std::end(heatmap_names)) throw json::other_error::create(501, "unknown heat map policy", &g);
  spec.heatmap = static_cast<grade::HeatMap>(named - std::begin(heatmap_names));
  spec.frames_from_page = g.at("framesFromPage");
  return spec;
}

json page_json(const render::PageSetup& p) {
  json uniforms = json::array();
  for (const auto& u : p.uniforms)
    uniforms.push_back({{"name", u.name}, {"type", u.glsl_type}, {"value", u.value}, {"components", u.components}});
  const auto& c = p.camera;
  return {{"fovYDegrees", c.fov_y_degrees}, {"near", c.near}, {"far", c.far},
          {"meshTranslation", {c.mesh_translation.x, c.mesh_translation.y, c.mesh_translation.z}}, {"uniforms", uniforms}};
}

render::PageSetup page_from(const json& j) {
  render::PageSetup p;
  p.camera.fov_y_degrees = j.at("fovYDegrees");
  p.camera.near = j.at("near");
  p.camera.far = j.at("far");
  p.camera.mesh_translation = j.at("meshTranslation").get<glm::dvec3>();
  for (const auto& u : j.at("uniforms"))
    p.uniforms.push_back({u.at("name"), u.at("type"), u.at("value").get<std::array<float, 4>>(), u.at("components")});
  return p;
}

json request_json(const render::RenderRequest& r) {
  json uniforms = json::array();
  for (const auto& u : r.uniforms) uniforms.push_back({{"name", u.name}, {"values", u.values}});
  return {{"vertex", file_json(r.vertex)}, {"fragment", file_json(r.fragment)}, {"width", r.width}, {"height", r.height},
          {"frames", r.frames}, {"degreesPerFrame", r.degrees_per_frame}, {"angles", r.angles}, {"msaa", r.msaa},
          {"page", page_json(r.page)}, {"uniforms", uniforms}, {"pixelType", r.pixel_type == image::PixelType::f32 ? "f32" : "u8"},
          {"semantics", r.semantics == render::FloatSemantics::ieee ? "ieee" : "asCompiled"}};
}

render::RenderRequest request_from(const json& j) {
  render::RenderRequest r;
  r.vertex = file_from(j.at("vertex"));
  r.fragment = file_from(j.at("fragment"));
  r.width = j.at("width");
  r.height = j.at("height");
  r.frames = j.at("frames");
  r.degrees_per_frame = j.at("degreesPerFrame");
  r.angles = j.at("angles").get<std::vector<double>>();
  r.msaa = j.at("msaa");
  r.page = page_from(j.at("page"));
  for (const auto& u : j.at("uniforms")) r.uniforms.push_back({u.at("name"), u.at("values").get<std::vector<double>>()});
  r.pixel_type = j.at("pixelType") == "f32" ? image::PixelType::f32 : image::PixelType::u8;
  r.semantics = j.at("semantics") == "ieee" ? render::FloatSemantics::ieee : render::FloatSemantics::as_compiled;
  return r;
}

template <class Enum, size_t N>
Enum enum_named(const json& j, const Enum (&values)[N]) {
  const std::string name = j.get<std::string>();
  for (const Enum v : values)
    if (to_string(v) == name) return v;
  throw json::other_error::create(501, "unknown value '" + name + "'", &j);
}

}  // namespace

std::string_view to_string(JobKind k) {
  switch (k) {
    case JobKind::render: return "render";
    case JobKind::compile: return "compile";
    case JobKind::mesh_check: return "mesh_check";
    case JobKind::grade: return "grade";
    case JobKind::grade_frames: return "grade_frames";
    case JobKind::scene: return "scene";
  }
  return "render";
}
std::string_view to_string(Output o) { return o == Output::grid ? "grid" : o == Output::frames ? "frames" : "json"; }
std::string_view to_string(Format f) { return f == Format::png ? "png" : "exr"; }

Message to_message(const Job& job, std::string mesh_bytes) {
  json fit = nullptr;
  if (job.fit) fit = {{"min", {job.fit->min.x, job.fit->min.y, job.fit->min.z}}, {"max", {job.fit->max.x, job.fit->max.y, job.fit->max.z}}};
  json header = {{"kind", to_string(job.kind)},     {"request", request_json(job.request)}, {"mesh", job.mesh},
                 {"meshEmbedded", job.mesh_embedded}, {"meshFormat", job.mesh_format},       {"fit", fit},
                 {"frameName", job.frame_name},     {"prefix", job.prefix},                 {"output", to_string(job.output)},
                 {"format", to_string(job.format)}, {"notice", job.notice}};
  if (job.kind == JobKind::grade || job.kind == JobKind::grade_frames) header["grade"] = grade_json(job.grade);
  return {std::move(header), std::move(mesh_bytes)};
}

Message to_message(const Job& job, const FramesPayload& payload) {
  Message m = to_message(job);
  std::vector<PayloadPartView> parts{{"mesh", payload.mesh}};
  for (const auto& f : payload.saved) parts.push_back({f.name, f.bytes});
  m.header["parts"] = pack_parts(parts, m.payload);
  return m;
}

Message to_message(const SceneJob& job) {
  Message m;
  std::vector<PayloadPartView> parts;
  json formats = json::array();
  for (const auto& mesh : job.meshes) {
    parts.push_back({mesh.reference, mesh.bytes});
    formats.push_back(mesh.format);
  }
  m.header = {{"kind", to_string(JobKind::scene)}, {"scene", to_json(job.scene)}, {"meshFormats", formats},
              {"meshes", pack_parts(parts, m.payload)}};
  return m;
}

Expected<JobKind> job_kind_of(const Message& m) {
  try {
    return enum_named(m.header.at("kind"), kKinds);
  } catch (const json::exception& e) {
    return make_error(ErrorCode::worker_protocol, std::string("a job without a known kind: ") + e.what());
  }
}

Expected<Job> job_from_message(const Message& m) {
  try {
    const json& j = m.header;
    Job job;
    job.kind = enum_named(j.at("kind"), kKinds);
    job.request = request_from(j.at("request"));
    job.mesh = j.at("mesh");
    job.mesh_embedded = j.at("meshEmbedded");
    job.mesh_format = j.at("meshFormat");
    if (const json& fit = j.at("fit"); !fit.is_null()) {
      const auto lo = fit.at("min").get<std::array<float, 3>>(), hi = fit.at("max").get<std::array<float, 3>>();
      job.fit = scene::Bounds{{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}};
    }
    job.frame_name = j.at("frameName");
    job.prefix = j.at("prefix");
    job.output = enum_named(j.at("output"), {Output::grid, Output::frames, Output::json});
    job.format = enum_named(j.at("format"), {Format::png, Format::exr});
    job.notice = j.at("notice");
    if (job.kind == JobKind::grade || job.kind == JobKind::grade_frames) job.grade = grade_from(j.at("grade"));
    return job;
  } catch (const json::exception& e) {
    return make_error(ErrorCode::worker_protocol, std::string("malformed job: ") + e.what());
  }
}

Expected<SceneJob> scene_job_from_message(const Message& m) {
  try {
    SceneJob job;
    job.scene = scene_from_json(m.header.at("scene"));
    auto parts = unpack_parts(m.header.at("meshes"), m.payload);
    if (!parts) return parts.take_error();
    const json& formats = m.header.at("meshFormats");
    if (formats.size() != parts->size()) return make_error(ErrorCode::worker_protocol, "a scene mesh without a format");
    for (size_t i = 0; i < parts->size(); ++i)
      job.meshes.push_back({std::move((*parts)[i].name), formats[i].get<std::string>(), std::move((*parts)[i].bytes)});
    return job;
  } catch (const json::exception& e) {
    return make_error(ErrorCode::worker_protocol, std::string("malformed scene job: ") + e.what());
  }
}

Expected<FramesPayload> frames_payload_from(const Message& m) {
  try {
    auto parts = unpack_parts(m.header.at("parts"), m.payload);
    if (!parts) return parts.take_error();
    if (parts->empty() || (*parts)[0].name != "mesh") return make_error(ErrorCode::worker_protocol, "a frames job without its mesh part");
    FramesPayload out{std::move((*parts)[0].bytes), {}};
    for (size_t i = 1; i < parts->size(); ++i) out.saved.push_back({std::move((*parts)[i].name), std::move((*parts)[i].bytes)});
    return out;
  } catch (const json::exception& e) {
    return make_error(ErrorCode::worker_protocol, std::string("malformed frames job: ") + e.what());
  }
}

json to_json(const scene::SceneDescription& s) {
  return {{"objects", s.objects}, {"ground", s.ground ? json(*s.ground) : json(nullptr)}, {"camera", s.camera},
          {"lights", s.lights},   {"world", s.world},                                   {"render", s.render}};
}

scene::SceneDescription scene_from_json(const json& j) {
  scene::SceneDescription s;
  j.at("objects").get_to(s.objects);
  if (!j.at("ground").is_null()) s.ground = j.at("ground").get<scene::Ground>();
  j.at("camera").get_to(s.camera);
  j.at("lights").get_to(s.lights);
  j.at("world").get_to(s.world);
  j.at("render").get_to(s.render);
  return s;
}

}  // namespace shadelab::worker
