#include "worker/result.h"

#include "core/json_fields.h"
#include "worker/scene_json.h"

using nlohmann::json;
using shadelab::json_fields::When;

namespace shadelab {

void to_json(json& j, const Error& e) {
  j = {{"code", to_string(e.code)}, {"message", e.message}, {"diagnostics", e.diagnostics}, {"driverLog", e.driver_log}};
}

void from_json(const json& j, Error& e) {
  e = {ErrorCode::worker_protocol, "a render worker reported an error it did not name", {}, {}};
  if (!j.is_object()) return;
  const auto code = error_code_named(worker::header_text(j, "code"));
  if (!code) {
    e.message = "a render worker reported an unknown error code " + (j.contains("code") ? j["code"] : json("")).dump();
    return;
  }
  e.code = *code;
  // A missing or non-string message is the code's title, never an empty detail or an exception.
  const auto text = [&j](const char* key) { return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : std::string(); };
  e.message = text("message");
  if (e.message.empty()) e.message = std::string(info(e.code).title);
  e.driver_log = text("driverLog");
  if (j.contains("diagnostics") && j["diagnostics"].is_array()) e.diagnostics = j["diagnostics"].get<std::vector<Diagnostic>>();
}

}  // namespace shadelab

namespace shadelab::grade {

SHADELAB_JSON_FIELDS(ImageVerdict, field("pass", &ImageVerdict::pass), field("message", &ImageVerdict::message),
                     field("leavesOut", &ImageVerdict::leaves_out))

}  // namespace shadelab::grade

namespace shadelab::repair {

SHADELAB_JSON_FIELDS(ValueChangeTo, field("reference", &ValueChangeTo::reference),
                     field("change", &ValueChangeTo::change, json_fields::Names{kValueChangeNames}))
SHADELAB_JSON_FIELDS(ValueAgreement, field("read", &ValueAgreement::read), field("agreesWith", &ValueAgreement::agrees_with),
                     field("differsVisibly", &ValueAgreement::differs_visibly),
                     field("compared", &ValueAgreement::compared), field("changes", &ValueAgreement::changes, When::default_when_missing))

}  // namespace shadelab::repair

namespace shadelab::render {

SHADELAB_JSON_FIELDS(VariableInfo, field("name", &VariableInfo::name), field("type", &VariableInfo::type),
                     field("arraySize", &VariableInfo::array_size))

}  // namespace shadelab::render

namespace shadelab::scene_render {

namespace {

constexpr json_fields::Names kTransformNames{scene::kViewTransformNames};
constexpr json_fields::Names kEngineNames{scene::kEngineNames};
constexpr json_fields::Names kProjections{scene::kProjectionNames};

// An object's box in the image, by its corners.
struct Corners {
  json write(const PixelBox& b) const { return {{"x0", b.min.x}, {"y0", b.min.y}, {"x1", b.max.x}, {"y1", b.max.y}}; }
  void read(const json& j, PixelBox& b) const {
    b = {{j.at("x0").get<double>(), j.at("y0").get<double>()}, {j.at("x1").get<double>(), j.at("y1").get<double>()}};
  }
};

// Each pass's detail is read by its pass's name.
PassDetail detail_from(const std::string& name, const json& d) {
  if (name == "setup") return SetupDetail{d.at("objects")};
  if (name == "shadow") return ShadowDetail{d.at("views"), d.at("size"), d.at("filterTaps")};
  if (name == "reflection") return ReflectionDetail{d.at("size"), d.at("levels")};
  if (name == "main") return MainDetail{d.at("objects"), d.at("ground"), d.at("samples"), d.at("shaderVariant")};
  if (name == "view") {
    ViewDetail view;
    kTransformNames.read(d.at("transform"), view.transform);
    return view;
  }
  if (name == "readback") return ReadbackDetail{};
  if (name == "framing") return FramingDetail{d.at("guardBandRenders")};
  throw json::other_error::create(501, "unknown pass '" + name + "'", &d);
}

json detail_json(const PassDetail& detail) {
  struct Visitor {
    json operator()(const SetupDetail& d) const { return {{"objects", d.objects}}; }
    json operator()(const ShadowDetail& d) const { return {{"views", d.views}, {"size", d.size}, {"filterTaps", d.filter_taps}}; }
    json operator()(const ReflectionDetail& d) const { return {{"size", d.size}, {"levels", d.levels}}; }
    json operator()(const MainDetail& d) const {
      return {{"objects", d.objects}, {"ground", d.ground}, {"samples", d.samples}, {"shaderVariant", d.shader_variant}};
    }
    json operator()(const ViewDetail& d) const { return {{"transform", scene::to_string(d.transform)}}; }
    json operator()(const ReadbackDetail&) const { return json::object(); }
    json operator()(const FramingDetail& d) const { return {{"guardBandRenders", d.guard_band_renders}}; }
  };
  return std::visit(Visitor{}, detail);
}

}  // namespace

void to_json(json& j, const PassTiming& p) { j = {{"name", p.name()}, {"ms", p.ms}, {"detail", detail_json(p.detail)}}; }
void from_json(const json& j, PassTiming& p) { p = {j.at("ms"), detail_from(j.at("name"), j.at("detail"))}; }

SHADELAB_JSON_FIELDS(ObjectFraming, field("name", &ObjectFraming::name), field("drawn", &ObjectFraming::drawn),
                     field("fullyVisible", &ObjectFraming::fully_visible), field("fractionInFrame", &ObjectFraming::fraction_in_frame),
                     field("imageCoverage", &ObjectFraming::image_coverage), field("visiblePixels", &ObjectFraming::visible_pixels),
                     field("behindCamera", &ObjectFraming::behind_camera), field("partlyBehindCamera", &ObjectFraming::partly_behind_camera),
                     field("boundingBox", &ObjectFraming::box, When::null_when_empty, Corners{}))

SHADELAB_JSON_FIELDS(CameraSummary, field("horizontalFov", &CameraSummary::horizontal_fov_degrees),
                     field("verticalFov", &CameraSummary::vertical_fov_degrees), field("type", &CameraSummary::type, kProjections))

SHADELAB_JSON_FIELDS(SceneReport, field("engine", &SceneReport::engine, kEngineNames),
                     field("viewTransform", &SceneReport::view_transform, kTransformNames), field("width", &SceneReport::width),
                     field("height", &SceneReport::height), field("passes", &SceneReport::passes), field("features", &SceneReport::features),
                     field("framing", &SceneReport::framing), field("camera", &SceneReport::camera), field("depth", &SceneReport::depth),
                     field("totalMs", &SceneReport::total_ms))

}  // namespace shadelab::scene_render

namespace shadelab::worker {

namespace {

// A mesh's bounds, together under one key.
struct MinMax {
  json write(const MeshCheckResult& r) const { return {{"min", r.min}, {"max", r.max}}; }
  void read(const json& j, MeshCheckResult& r) const {
    j.at("min").get_to(r.min);
    j.at("max").get_to(r.max);
  }
};

}  // namespace

SHADELAB_JSON_FIELDS(ConstantFrame, field("frame", &ConstantFrame::frame), field("rgba", &ConstantFrame::rgba))

SHADELAB_JSON_FIELDS(RenderTimings, field("compile", &RenderTimings::compile_ms), field("upload", &RenderTimings::upload_ms),
                     field("firstFrame", &RenderTimings::first_frame_ms), field("render", &RenderTimings::render_ms),
                     field("readback", &RenderTimings::readback_ms), field("encode", &RenderTimings::encode_ms))

SHADELAB_JSON_FIELDS(CompileResult, field("warnings", &CompileResult::warnings), field("diagnostics", &CompileResult::diagnostics),
                     field("attributes", &CompileResult::attributes), field("uniforms", &CompileResult::uniforms),
                     field("compileMs", &CompileResult::compile_ms))

SHADELAB_JSON_FIELDS(RenderResult, field("warnings", &RenderResult::warnings), field("diagnostics", &RenderResult::diagnostics),
                     field("attributes", &RenderResult::attributes), field("uniforms", &RenderResult::uniforms),
                     field("samples", &RenderResult::samples), field("constantFrames", &RenderResult::constant_frames),
                     field("timings", &RenderResult::timings), field("contentType", &RenderResult::content_type))

SHADELAB_JSON_FIELDS(MeshCheckResult, field("triangles", &MeshCheckResult::triangles),
                     field("normalsFromFile", &MeshCheckResult::normals_from_file),
                     at("bounds", [](auto& r) -> auto& { return r; }, When::required, MinMax{}))

SHADELAB_JSON_FIELDS(SceneResult, field("report", &SceneResult::report), field("encodeMs", &SceneResult::encode_ms))
SHADELAB_JSON_FIELDS(GradeResult, field("report", &GradeResult::report), field("values", &GradeResult::values, When::omitted_when_empty))
SHADELAB_JSON_FIELDS(FramesGradeResult, field("frames", &FramesGradeResult::frames),
                     field("code", &FramesGradeResult::code, When::null_when_empty))
SHADELAB_JSON_FIELDS(ImagesResult, field("verdicts", &ImagesResult::verdicts))

namespace {

// The files each result carries beside its JSON, by name.
std::vector<PayloadPartView> files_of(const RenderResult& r) {
  std::vector<PayloadPartView> files{{"body", r.body}};
  for (const auto& f : r.frames) files.push_back({f.name, f.bytes});
  return files;
}
std::vector<PayloadPartView> files_of(const SceneResult& r) { return {{"image.png", r.png}}; }
std::vector<PayloadPartView> heatmap_file(const std::string& png) {
  if (png.empty()) return {};
  return {{"heatmap.png", png}};
}
std::vector<PayloadPartView> files_of(const GradeResult& r) { return heatmap_file(r.heatmap_png); }
std::vector<PayloadPartView> files_of(const FramesGradeResult& r) { return heatmap_file(r.heatmap_png); }
std::vector<PayloadPartView> files_of(const CompileResult&) { return {}; }
std::vector<PayloadPartView> files_of(const MeshCheckResult&) { return {}; }
std::vector<PayloadPartView> files_of(const ImagesResult&) { return {}; }

// The file of an answer of that name, moved out; empty when there is none.
std::string take_file(std::vector<PayloadPart>& files, std::string_view name) {
  for (auto& f : files)
    if (f.name == name) return std::move(f.bytes);
  return {};
}

void take_files(RenderResult& r, std::vector<PayloadPart>& files) {
  for (auto& f : files) {
    if (f.name == "body") r.body = std::move(f.bytes);
    else r.frames.push_back({std::move(f.name), std::move(f.bytes)});
  }
}
void take_files(SceneResult& r, std::vector<PayloadPart>& files) { r.png = take_file(files, "image.png"); }
void take_files(GradeResult& r, std::vector<PayloadPart>& files) { r.heatmap_png = take_file(files, "heatmap.png"); }
void take_files(FramesGradeResult& r, std::vector<PayloadPart>& files) { r.heatmap_png = take_file(files, "heatmap.png"); }
void take_files(CompileResult&, std::vector<PayloadPart>&) {}
void take_files(MeshCheckResult&, std::vector<PayloadPart>&) {}
void take_files(ImagesResult&, std::vector<PayloadPart>&) {}

template <class Result>
Message ok(const Result& r) {
  Message m;
  json index = pack_parts(files_of(r), m.payload);
  m.header = {{"ok", true}, {"result", r}, {"files", std::move(index)}};
  return m;
}

}  // namespace

Message answer(const CompileResult& r) { return ok(r); }
Message answer(const RenderResult& r) { return ok(r); }
Message answer(const MeshCheckResult& r) { return ok(r); }
Message answer(const SceneResult& r) { return ok(r); }
Message answer(const GradeResult& r) { return ok(r); }
Message answer(const FramesGradeResult& r) { return ok(r); }
Message answer(const ImagesResult& r) { return ok(r); }
Message answer(const Error& e) { return {{{"ok", false}, {"error", e}}, {}}; }

template <class Result>
Expected<Result> result_from(const Message& m) {
  if (!m.header.is_object()) return make_error(ErrorCode::worker_protocol, "a render worker's answer is not an object");
  if (!header_flag(m.header, "ok")) return (m.header.contains("error") ? m.header["error"] : json::object()).get<Error>();
  try {
    auto files = unpack_parts(m.header.at("files"), m.payload);
    if (!files) return files.take_error();
    auto result = m.header.at("result").get<Result>();
    take_files(result, *files);
    return result;
  } catch (const json::exception& e) {
    return make_error(ErrorCode::worker_protocol, std::string("a render worker's answer is malformed: ") + e.what());
  }
}

template Expected<CompileResult> result_from(const Message&);
template Expected<RenderResult> result_from(const Message&);
template Expected<MeshCheckResult> result_from(const Message&);
template Expected<SceneResult> result_from(const Message&);
template Expected<GradeResult> result_from(const Message&);
template Expected<FramesGradeResult> result_from(const Message&);
template Expected<ImagesResult> result_from(const Message&);

}  // namespace shadelab::worker
