#include "worker/job.h"

#include <array>
#include <initializer_list>

#include "core/enum_names.h"
#include "core/json_enum.h"
#include "worker/scene_json.h"

// The job wire: one to_json / from_json pair per struct, in the struct's own namespace (where
// nlohmann finds it). from_json throws nlohmann::json::exception on a malformed job.

using nlohmann::json;

namespace shadelab::shader {
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ShaderFile, name, text)
}  // namespace shadelab::shader

namespace shadelab::store {

void to_json(json& j, const SharedStoreConfig& s) {
  j = {{"url", s.url}, {"timeoutMs", s.timeout.count()}, {"retryAfterMs", s.retry_after.count()},
       {"timeToLiveS", s.time_to_live.count()}, {"maxValueBytes", s.max_value_bytes}};
}

void from_json(const json& j, SharedStoreConfig& s) {
  s.url = j.at("url");
  s.timeout = std::chrono::milliseconds(j.at("timeoutMs").get<long long>());
  s.retry_after = std::chrono::milliseconds(j.at("retryAfterMs").get<long long>());
  s.time_to_live = std::chrono::seconds(j.at("timeToLiveS").get<long long>());
  s.max_value_bytes = j.at("maxValueBytes");
}

}  // namespace shadelab::store

namespace shadelab::grade {

void to_json(json& j, const FormulaReading& r) {
  j = {{"variant", std::string(model::info(r.variant).id)}, {"values", json::array()}};
  for (const auto& v : r.values) j["values"].push_back({{"parameter", model::to_string(v.parameter)}, {"value", v.value}});
}
void from_json(const json& j, FormulaReading& r) {
  const auto variant = model::variant_named(j.at("variant").get<std::string>());
  if (!variant) throw json::other_error::create(501, "unknown variant", &j);
  r.variant = *variant;
  for (const auto& v : j.at("values")) {
    const auto parameter = model::parameter_named(v.at("parameter").get<std::string>());
    if (!parameter) throw json::other_error::create(501, "unknown parameter", &v);
    r.values.push_back({*parameter, v.at("value").get<std::vector<double>>()});
  }
}

void to_json(json& j, const Mistake& m) {
  j = {{"id", m.id}, {"message", m.message}, {"vertex", m.vertex}, {"fragment", m.fragment}};
  if (m.reading) j["reading"] = *m.reading;
}
void from_json(const json& j, Mistake& m) {
  j.at("id").get_to(m.id);
  j.at("message").get_to(m.message);
  j.at("vertex").get_to(m.vertex);
  j.at("fragment").get_to(m.fragment);
  if (j.contains("reading")) m.reading = j.at("reading").get<FormulaReading>();
}
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(StarterConstant, variable, meaning, value)

void to_json(json& j, const Probe& p) {
  j = {{"name", p.name}, {"checks", p.checks}};
  if (p.light_position) j["lightPosition"] = *p.light_position;
  if (p.light_color) j["lightColor"] = *p.light_color;
}
void from_json(const json& j, Probe& p) {
  p = {j.at("name"), std::nullopt, std::nullopt, j.value("checks", "")};
  if (j.contains("lightPosition")) p.light_position = j.at("lightPosition").get<std::array<float, 3>>();
  if (j.contains("lightColor")) p.light_color = j.at("lightColor").get<std::array<float, 3>>();
}
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ProbeUniform, names, type)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(FormulaInput, names, value, alpha)

void to_json(json& j, const FormulaSpec& f) {
  j = {{"terms", model::to_string(f.terms)}, {"positionVarying", f.position_varying}, {"normalVarying", f.normal_varying},
       {"colourVarying", f.colour_varying}, {"geometryVertex", f.geometry_vertex}, {"ambient", f.ambient}, {"diffuse", f.diffuse}, {"specular", f.specular}, {"lightPosition", f.light_position},
       {"lightColour", f.light_colour}, {"exponent", f.exponent}};
}
void from_json(const json& j, FormulaSpec& f) {
  f.terms = enum_from_json(j.at("terms"), {model::Terms::lambert, model::Terms::phong, model::Terms::normal_colour});
  j.at("positionVarying").get_to(f.position_varying);
  j.at("normalVarying").get_to(f.normal_varying);
  j.at("colourVarying").get_to(f.colour_varying);
  j.at("geometryVertex").get_to(f.geometry_vertex);
  j.at("ambient").get_to(f.ambient);
  j.at("diffuse").get_to(f.diffuse);
  j.at("specular").get_to(f.specular);
  j.at("lightPosition").get_to(f.light_position);
  j.at("lightColour").get_to(f.light_colour);
  j.at("exponent").get_to(f.exponent);
}

constexpr EnumName<HeatMap> kHeatMaps[] = {{HeatMap::always, "always"}, {HeatMap::when_failing, "whenFailing"}, {HeatMap::never, "never"}};

// The options and the reference store's places travel flat, beside the spec's own fields.
void to_json(json& j, const GradeSpec& g) {
  const auto& o = g.options;
  j = {{"referenceName", g.reference_name}, {"referenceVertex", g.reference_vertex}, {"referenceFragment", g.reference_fragment},
       {"mistakes", g.mistakes}, {"probes", g.probes}, {"lightPositionUniforms", g.light_position_uniforms}, {"lightColorUniform", g.light_color_uniform},
       {"starterConstants", g.starter_constants}, {"referenceStore", g.reference_store.folder},
       {"sharedStore", g.reference_store.shared}, {"threshold", o.compare.threshold},
       {"spatialTolerance", o.compare.spatial_tolerance}, {"maxFailingFraction", o.max_failing_fraction},
       {"maxScore", o.max_score}, {"sameOutline", o.same_outline},
       {"savedFramesCloserThanReference", o.saved_frames_closer_than_reference},
       {"heatmap", name_in(kHeatMaps, g.heatmap)}, {"framesFromPage", g.frames_from_page}};
  if (g.formula) j["formula"] = *g.formula;
}

void from_json(const json& j, GradeSpec& g) {
  j.at("referenceName").get_to(g.reference_name);
  j.at("referenceVertex").get_to(g.reference_vertex);
  j.at("referenceFragment").get_to(g.reference_fragment);
  j.at("mistakes").get_to(g.mistakes);
  j.at("probes").get_to(g.probes);
  j.at("lightPositionUniforms").get_to(g.light_position_uniforms);
  j.at("lightColorUniform").get_to(g.light_color_uniform);
  j.at("starterConstants").get_to(g.starter_constants);
  j.at("referenceStore").get_to(g.reference_store.folder);
  j.at("sharedStore").get_to(g.reference_store.shared);
  auto& o = g.options;
  j.at("threshold").get_to(o.compare.threshold);
  j.at("spatialTolerance").get_to(o.compare.spatial_tolerance);
  j.at("maxFailingFraction").get_to(o.max_failing_fraction);
  j.at("maxScore").get_to(o.max_score);
  j.at("sameOutline").get_to(o.same_outline);
  j.at("savedFramesCloserThanReference").get_to(o.saved_frames_closer_than_reference);
  const auto heatmap = value_in(kHeatMaps, j.at("heatmap").get<std::string>());
  if (!heatmap) throw json::other_error::create(501, "unknown heat map policy", &j);
  g.heatmap = *heatmap;
  j.at("framesFromPage").get_to(g.frames_from_page);
  if (j.contains("formula")) g.formula = j.at("formula").get<FormulaSpec>();
}

}  // namespace shadelab::grade

namespace shadelab::render {

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(UniformSetting, name, values)

void to_json(json& j, const ConstantUniform& u) {
  j = {{"name", u.name}, {"type", u.glsl_type}, {"value", u.value}, {"components", u.components}};
}
void from_json(const json& j, ConstantUniform& u) { u = {j.at("name"), j.at("type"), j.at("value"), j.at("components")}; }

// The camera travels flat, beside the page's uniforms.
void to_json(json& j, const PageSetup& p) {
  const auto& c = p.camera;
  j = {{"fovYDegrees", c.fov_y_degrees}, {"near", c.near}, {"far", c.far}, {"meshTranslation", c.mesh_translation},
       {"uniforms", p.uniforms}};
}

void from_json(const json& j, PageSetup& p) {
  j.at("fovYDegrees").get_to(p.camera.fov_y_degrees);
  j.at("near").get_to(p.camera.near);
  j.at("far").get_to(p.camera.far);
  j.at("meshTranslation").get_to(p.camera.mesh_translation);
  j.at("uniforms").get_to(p.uniforms);
}

void to_json(json& j, const RenderRequest& r) {
  j = {{"vertex", r.vertex}, {"fragment", r.fragment}, {"width", r.width}, {"height", r.height}, {"frames", r.frames},
       {"degreesPerFrame", r.degrees_per_frame}, {"angles", r.angles}, {"msaa", r.msaa}, {"samplePosition", r.sample_position ? json(*r.sample_position) : json(nullptr)}, {"page", r.page},
       {"uniforms", r.uniforms}, {"pixelType", r.pixel_type == image::PixelType::f32 ? "f32" : "u8"},
       {"semantics", r.semantics == FloatSemantics::ieee ? "ieee" : "asCompiled"}};
}

void from_json(const json& j, RenderRequest& r) {
  j.at("vertex").get_to(r.vertex);
  j.at("fragment").get_to(r.fragment);
  j.at("width").get_to(r.width);
  j.at("height").get_to(r.height);
  j.at("frames").get_to(r.frames);
  j.at("degreesPerFrame").get_to(r.degrees_per_frame);
  j.at("angles").get_to(r.angles);
  j.at("msaa").get_to(r.msaa);
  if (const auto at = j.find("samplePosition"); at != j.end() && !at->is_null()) r.sample_position = at->get<std::array<double, 2>>();
  j.at("page").get_to(r.page);
  j.at("uniforms").get_to(r.uniforms);
  r.pixel_type = j.at("pixelType") == "f32" ? image::PixelType::f32 : image::PixelType::u8;
  r.semantics = j.at("semantics") == "ieee" ? FloatSemantics::ieee : FloatSemantics::as_compiled;
}

}  // namespace shadelab::render

namespace shadelab::scene {

void to_json(json& j, const Bounds& b) { j = {{"min", {b.min.x, b.min.y, b.min.z}}, {"max", {b.max.x, b.max.y, b.max.z}}}; }

void from_json(const json& j, Bounds& b) {
  const auto lo = j.at("min").get<std::array<float, 3>>(), hi = j.at("max").get<std::array<float, 3>>();
  b = {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}};
}

void to_json(json& j, const SceneDescription& s) {
  j = {{"objects", s.objects}, {"ground", s.ground ? json(*s.ground) : json(nullptr)}, {"camera", s.camera},
       {"lights", s.lights},   {"world", s.world},                                   {"render", s.render}};
}

void from_json(const json& j, SceneDescription& s) {
  j.at("objects").get_to(s.objects);
  s.ground = j.at("ground").is_null() ? std::nullopt : std::optional<Ground>(j.at("ground").get<Ground>());
  j.at("camera").get_to(s.camera);
  j.at("lights").get_to(s.lights);
  j.at("world").get_to(s.world);
  j.at("render").get_to(s.render);
}

}  // namespace shadelab::scene

namespace shadelab::worker {

namespace {

constexpr std::initializer_list<JobKind> kKinds = {JobKind::render, JobKind::compile, JobKind::mesh_check, JobKind::grade,
                                                   JobKind::grade_frames, JobKind::scene, JobKind::check_images};

bool is_grade(JobKind k) { return k == JobKind::grade || k == JobKind::grade_frames; }

}  // namespace

void to_json(json& j, const Job& job) {
  j = {{"kind", to_string(job.kind)},     {"request", job.request},     {"mesh", job.mesh},
       {"meshEmbedded", job.mesh_embedded}, {"meshFormat", job.mesh_format}, {"fit", job.fit ? json(*job.fit) : json(nullptr)},
       {"frameName", job.frame_name},     {"prefix", job.prefix},       {"output", to_string(job.output)},
       {"format", to_string(job.format)}, {"notice", job.notice}};
  if (is_grade(job.kind)) j["grade"] = job.grade;
}

void from_json(const json& j, Job& job) {
  job.kind = enum_from_json(j.at("kind"), kKinds);
  j.at("request").get_to(job.request);
  j.at("mesh").get_to(job.mesh);
  j.at("meshEmbedded").get_to(job.mesh_embedded);
  j.at("meshFormat").get_to(job.mesh_format);
  if (const json& fit = j.at("fit"); !fit.is_null()) job.fit = fit.get<scene::Bounds>();
  j.at("frameName").get_to(job.frame_name);
  j.at("prefix").get_to(job.prefix);
  job.output = enum_from_json(j.at("output"), {Output::grid, Output::frames, Output::json});
  job.format = enum_from_json(j.at("format"), {Format::png, Format::exr});
  j.at("notice").get_to(job.notice);
  if (is_grade(job.kind)) j.at("grade").get_to(job.grade);
}

std::string_view to_string(JobKind k) {
  switch (k) {
    case JobKind::render: return "render";
    case JobKind::compile: return "compile";
    case JobKind::mesh_check: return "mesh_check";
    case JobKind::grade: return "grade";
    case JobKind::grade_frames: return "grade_frames";
    case JobKind::scene: return "scene";
    case JobKind::check_images: return "check_images";
  }
  return "render";
}
std::string_view to_string(Output o) { return o == Output::grid ? "grid" : o == Output::frames ? "frames" : "json"; }
std::string_view to_string(Format f) { return f == Format::png ? "png" : "exr"; }

Message to_message(const Job& job, std::string mesh_bytes) { return {json(job), std::move(mesh_bytes)}; }

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
  m.header = {{"kind", to_string(JobKind::scene)}, {"scene", job.scene}, {"meshFormats", formats},
              {"meshes", pack_parts(parts, m.payload)}};
  return m;
}

Message to_message(const ImagesJob& job) {
  Message m;
  std::vector<PayloadPartView> parts;
  json images = json::array();
  for (const auto& image : job.images) {
    images.push_back({{"file", image.file}, {"scene", image.scene ? json(*image.scene) : json(nullptr)}, {"objects", image.objects},
                      {"problem", image.problem}});
    parts.push_back({image.file, image.png});
  }
  m.header = {{"kind", to_string(JobKind::check_images)}, {"images", images}, {"pngs", pack_parts(parts, m.payload)}};
  return m;
}

Expected<JobKind> job_kind_of(const Message& m) {
  try {
    return enum_from_json(m.header.at("kind"), kKinds);
  } catch (const json::exception& e) {
    return make_error(ErrorCode::worker_protocol, std::string("a job without a known kind: ") + e.what());
  }
}

Expected<Job> job_from_message(const Message& m) {
  try {
    return m.header.get<Job>();
  } catch (const json::exception& e) {
    return make_error(ErrorCode::worker_protocol, std::string("malformed job: ") + e.what());
  }
}

Expected<SceneJob> scene_job_from_message(const Message& m) {
  try {
    SceneJob job;
    m.header.at("scene").get_to(job.scene);
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

Expected<ImagesJob> images_job_from_message(const Message& m) {
  try {
    auto pngs = unpack_parts(m.header.at("pngs"), m.payload);
    if (!pngs) return pngs.take_error();
    const json& images = m.header.at("images");
    if (images.size() != pngs->size()) return make_error(ErrorCode::worker_protocol, "a checked image without its bytes");
    ImagesJob job;
    for (size_t i = 0; i < pngs->size(); ++i) {
      const json& image = images[i];
      CheckedImage c{image.at("file").get<std::string>(), std::nullopt, image.at("objects").get<int>(), std::move((*pngs)[i].bytes),
                     image.at("problem").get<std::string>()};
      if (!image.at("scene").is_null()) c.scene = image.at("scene").get<scene::SceneDescription>();
      job.images.push_back(std::move(c));
    }
    return job;
  } catch (const json::exception& e) {
    return make_error(ErrorCode::worker_protocol, std::string("malformed image check: ") + e.what());
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

}  // namespace shadelab::worker
