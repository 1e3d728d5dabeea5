#include "worker/job.h"

#include <array>
#include <initializer_list>

#include "core/json_fields.h"
#include "worker/scene_json.h"

// The job wire: each struct's fields declared once (core/json_fields.h), in the struct's own
// namespace (where nlohmann finds them). from_json throws nlohmann::json::exception on a malformed job.

using nlohmann::json;
using shadelab::json_fields::When;

namespace shadelab::shader {
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ShaderFile, name, text)
}  // namespace shadelab::shader

namespace shadelab::store {

SHADELAB_JSON_FIELDS(SharedStoreConfig, field("url", &SharedStoreConfig::url), field("timeoutMs", &SharedStoreConfig::timeout, Count{}),
                     field("retryAfterMs", &SharedStoreConfig::retry_after, Count{}),
                     field("timeToLiveS", &SharedStoreConfig::time_to_live, Count{}),
                     field("maxValueBytes", &SharedStoreConfig::max_value_bytes))

}  // namespace shadelab::store

namespace shadelab::grade {

namespace {
std::string_view variant_id(model::Variant v) { return model::info(v).id; }
constexpr json_fields::Named<model::Variant> kVariantIds{variant_id, model::variant_named};
constexpr json_fields::Named<model::Parameter> kParameterNames{model::to_string, model::parameter_named};
constexpr json_fields::Named<model::Terms> kTermsNames{model::to_string, model::terms_named};
constexpr EnumName<HeatMap> kHeatMapNames[] = {{HeatMap::always, "always"}, {HeatMap::when_failing, "whenFailing"}, {HeatMap::never, "never"}};
constexpr json_fields::Names kHeatMaps{kHeatMapNames};
constexpr json_fields::Names kDifferencePictures{kDifferencePictureNames};
}  // namespace

SHADELAB_JSON_FIELDS(FormulaReading::Value, field("parameter", &FormulaReading::Value::parameter, kParameterNames),
                     field("value", &FormulaReading::Value::value))
SHADELAB_JSON_FIELDS(FormulaReading, field("variant", &FormulaReading::variant, kVariantIds), field("values", &FormulaReading::values))
SHADELAB_JSON_FIELDS(Mistake, field("id", &Mistake::id), field("message", &Mistake::message), field("vertex", &Mistake::vertex),
                     field("fragment", &Mistake::fragment), field("reading", &Mistake::reading, When::omitted_when_empty))
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(StarterConstant, variable, meaning, value)
SHADELAB_JSON_FIELDS(Probe, field("name", &Probe::name), field("lightPosition", &Probe::light_position, When::omitted_when_empty),
                     field("lightColor", &Probe::light_color, When::omitted_when_empty),
                     field("checks", &Probe::checks, When::default_when_missing))
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ProbeUniform, names, type)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(FormulaInput, names, value, alpha)

SHADELAB_JSON_FIELDS(FormulaSpec, field("terms", &FormulaSpec::terms, kTermsNames), field("positionVarying", &FormulaSpec::position_varying),
                     field("normalVarying", &FormulaSpec::normal_varying), field("colourVarying", &FormulaSpec::colour_varying),
                     field("geometryVertex", &FormulaSpec::geometry_vertex), field("ambient", &FormulaSpec::ambient),
                     field("diffuse", &FormulaSpec::diffuse), field("specular", &FormulaSpec::specular),
                     field("lightPosition", &FormulaSpec::light_position), field("lightColour", &FormulaSpec::light_colour),
                     field("exponent", &FormulaSpec::exponent))

// The options and the reference store's places travel flat, beside the spec's own fields.
SHADELAB_JSON_FIELDS(GradeSpec, field("referenceName", &GradeSpec::reference_name), field("referenceVertex", &GradeSpec::reference_vertex),
                     field("referenceFragment", &GradeSpec::reference_fragment), field("mistakes", &GradeSpec::mistakes),
                     field("probes", &GradeSpec::probes), field("lightPositionUniforms", &GradeSpec::light_position_uniforms),
                     field("lightColorUniform", &GradeSpec::light_color_uniform), field("starterConstants", &GradeSpec::starter_constants),
                     at("referenceStore", [](auto& g) -> auto& { return g.reference_store.folder; }),
                     at("sharedStore", [](auto& g) -> auto& { return g.reference_store.shared; }),
                     at("threshold", [](auto& g) -> auto& { return g.options.compare.threshold; }),
                     at("spatialTolerance", [](auto& g) -> auto& { return g.options.compare.spatial_tolerance; }),
                     at("maxFailingFraction", [](auto& g) -> auto& { return g.options.max_failing_fraction; }),
                     at("maxScore", [](auto& g) -> auto& { return g.options.max_score; }),
                     at("sameOutline", [](auto& g) -> auto& { return g.options.same_outline; }),
                     at("savedFramesCloserThanReference", [](auto& g) -> auto& { return g.options.saved_frames_closer_than_reference; }),
                     field("heatmap", &GradeSpec::heatmap, kHeatMaps),
                     field("picture", &GradeSpec::picture, kDifferencePictures), field("framesFromPage", &GradeSpec::frames_from_page),
                     field("formula", &GradeSpec::formula, When::omitted_when_empty), field("warm", &GradeSpec::warm, When::omitted_when_default),
                     field("readValues", &GradeSpec::read_values, When::omitted_when_default))

// A handed-in image's bytes travel in the payload, beside the JSON (worker/job.cpp's to_message).
SHADELAB_JSON_FIELDS(HandInImage, field("file", &HandInImage::file), field("scene", &HandInImage::scene, When::null_when_empty),
                     field("objects", &HandInImage::objects), field("problem", &HandInImage::problem))

}  // namespace shadelab::grade

namespace shadelab::render {

namespace {
constexpr EnumName<image::PixelType> kPixelTypeNames[] = {{image::PixelType::u8, "u8"}, {image::PixelType::f32, "f32"}};
constexpr json_fields::Names kPixelTypes{kPixelTypeNames};
constexpr EnumName<FloatSemantics> kSemanticsNames[] = {{FloatSemantics::as_compiled, "asCompiled"}, {FloatSemantics::ieee, "ieee"}};
constexpr json_fields::Names kSemantics{kSemanticsNames};
}  // namespace

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(UniformSetting, name, values)

SHADELAB_JSON_FIELDS(ConstantUniform, field("name", &ConstantUniform::name), field("type", &ConstantUniform::glsl_type),
                     field("value", &ConstantUniform::value), field("components", &ConstantUniform::components))

// The camera travels flat, beside the page's uniforms.
SHADELAB_JSON_FIELDS(PageSetup, at("fovYDegrees", [](auto& p) -> auto& { return p.camera.fov_y_degrees; }),
                     at("near", [](auto& p) -> auto& { return p.camera.near; }), at("far", [](auto& p) -> auto& { return p.camera.far; }),
                     at("meshTranslation", [](auto& p) -> auto& { return p.camera.mesh_translation; }),
                     field("uniforms", &PageSetup::uniforms))

SHADELAB_JSON_FIELDS(RenderRequest, field("vertex", &RenderRequest::vertex), field("fragment", &RenderRequest::fragment),
                     field("width", &RenderRequest::width), field("height", &RenderRequest::height), field("frames", &RenderRequest::frames),
                     field("degreesPerFrame", &RenderRequest::degrees_per_frame), field("angles", &RenderRequest::angles),
                     field("msaa", &RenderRequest::msaa), field("samplePosition", &RenderRequest::sample_position, When::null_when_empty),
                     field("page", &RenderRequest::page), field("uniforms", &RenderRequest::uniforms),
                     field("pixelType", &RenderRequest::pixel_type, kPixelTypes), field("semantics", &RenderRequest::semantics, kSemantics))

}  // namespace shadelab::render

namespace shadelab::scene {

void to_json(json& j, const Bounds& b) { j = {{"min", {b.min.x, b.min.y, b.min.z}}, {"max", {b.max.x, b.max.y, b.max.z}}}; }

void from_json(const json& j, Bounds& b) {
  const auto lo = j.at("min").get<std::array<float, 3>>(), hi = j.at("max").get<std::array<float, 3>>();
  b = {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}};
}

SHADELAB_JSON_FIELDS(SceneDescription, field("objects", &SceneDescription::objects),
                     field("ground", &SceneDescription::ground, When::null_when_empty), field("camera", &SceneDescription::camera),
                     field("lights", &SceneDescription::lights), field("world", &SceneDescription::world),
                     field("render", &SceneDescription::render))

}  // namespace shadelab::scene

namespace shadelab::worker {

namespace {

constexpr auto kKinds = json_fields::by_to_string(JobKind::render, JobKind::compile, JobKind::mesh_check, JobKind::grade,
                                                  JobKind::grade_frames, JobKind::scene, JobKind::check_images);

bool is_grade(JobKind k) { return k == JobKind::grade || k == JobKind::grade_frames; }

}  // namespace

SHADELAB_JSON_FIELDS(Job, field("kind", &Job::kind, kKinds), field("request", &Job::request), field("mesh", &Job::mesh),
                     field("meshEmbedded", &Job::mesh_embedded), field("meshFormat", &Job::mesh_format),
                     field("fit", &Job::fit, When::null_when_empty), field("frameName", &Job::frame_name), field("prefix", &Job::prefix),
                     field("output", &Job::output, json_fields::by_to_string(Output::grid, Output::frames, Output::json)),
                     field("format", &Job::format, json_fields::by_to_string(Format::png, Format::exr)), field("notice", &Job::notice),
                     only_where([](const Job& job) { return is_grade(job.kind); }, field("grade", &Job::grade)),
                     field("deadlineShare", &Job::deadline_share, When::omitted_when_empty))

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
  for (const auto& image : job.images) parts.push_back({image.file, image.png});
  m.header = {{"kind", to_string(JobKind::check_images)}, {"images", job.images}, {"pngs", pack_parts(parts, m.payload)}};
  return m;
}

namespace {

// What `read` makes of a message, or worker_protocol saying what was malformed in it.
template <class Read>
auto read_message_as(const char* what, Read read) -> decltype(read()) {
  try {
    return read();
  } catch (const json::exception& e) {
    return make_error(ErrorCode::worker_protocol, std::string(what) + ": " + e.what());
  }
}

}  // namespace

Expected<JobKind> job_kind_of(const Message& m) {
  return read_message_as("a job without a known kind", [&]() -> Expected<JobKind> {
    JobKind kind{};
    kKinds.read(m.header.at("kind"), kind);
    return kind;
  });
}

Expected<Job> job_from_message(const Message& m) {
  return read_message_as("malformed job", [&]() -> Expected<Job> { return m.header.get<Job>(); });
}

Expected<SceneJob> scene_job_from_message(const Message& m) {
  return read_message_as("malformed scene job", [&]() -> Expected<SceneJob> {
    SceneJob job;
    m.header.at("scene").get_to(job.scene);
    auto parts = unpack_parts(m.header.at("meshes"), m.payload);
    if (!parts) return parts.take_error();
    const json& formats = m.header.at("meshFormats");
    if (formats.size() != parts->size()) return make_error(ErrorCode::worker_protocol, "a scene mesh without a format");
    for (size_t i = 0; i < parts->size(); ++i)
      job.meshes.push_back({std::move((*parts)[i].name), formats[i].get<std::string>(), std::move((*parts)[i].bytes)});
    return job;
  });
}

Expected<ImagesJob> images_job_from_message(const Message& m) {
  return read_message_as("malformed image check", [&]() -> Expected<ImagesJob> {
    auto pngs = unpack_parts(m.header.at("pngs"), m.payload);
    if (!pngs) return pngs.take_error();
    ImagesJob job{m.header.at("images").get<std::vector<CheckedImage>>()};
    if (job.images.size() != pngs->size()) return make_error(ErrorCode::worker_protocol, "a checked image without its bytes");
    for (size_t i = 0; i < pngs->size(); ++i) job.images[i].png = std::move((*pngs)[i].bytes);
    return job;
  });
}

Expected<FramesPayload> frames_payload_from(const Message& m) {
  return read_message_as("malformed frames job", [&]() -> Expected<FramesPayload> {
    auto parts = unpack_parts(m.header.at("parts"), m.payload);
    if (!parts) return parts.take_error();
    if (parts->empty() || (*parts)[0].name != "mesh") return make_error(ErrorCode::worker_protocol, "a frames job without its mesh part");
    FramesPayload out{std::move((*parts)[0].bytes), {}};
    for (size_t i = 1; i < parts->size(); ++i) out.saved.push_back({std::move((*parts)[i].name), std::move((*parts)[i].bytes)});
    return out;
  });
}

}  // namespace shadelab::worker
