#include "worker/result.h"

#include "core/json_enum.h"
#include "worker/scene_json.h"

using nlohmann::json;

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

void to_json(json& j, const ImageVerdict& v) { j = {{"pass", v.pass}, {"message", v.message}, {"leavesOut", v.leaves_out}}; }
void from_json(const json& j, ImageVerdict& v) {
  j.at("pass").get_to(v.pass);
  j.at("message").get_to(v.message);
  j.at("leavesOut").get_to(v.leaves_out);
}

}  // namespace shadelab::grade

namespace shadelab::render {

void to_json(json& j, const VariableInfo& v) { j = {{"name", v.name}, {"type", v.type}, {"arraySize", v.array_size}}; }
void from_json(const json& j, VariableInfo& v) { v = {j.at("name"), j.at("type"), j.at("arraySize")}; }

}  // namespace shadelab::render

namespace shadelab::scene_render {

namespace {

constexpr auto kTransforms = {scene::ViewTransform::standard, scene::ViewTransform::filmic};

// Each pass's detail is read by its pass's name.
PassDetail detail_from(const std::string& name, const json& d) {
  if (name == "setup") return SetupDetail{d.at("objects")};
  if (name == "shadow") return ShadowDetail{d.at("views"), d.at("size"), d.at("filterTaps")};
  if (name == "reflection") return ReflectionDetail{d.at("size"), d.at("levels")};
  if (name == "main") return MainDetail{d.at("objects"), d.at("ground"), d.at("samples"), d.at("shaderVariant")};
  if (name == "view") return ViewDetail{enum_from_json(d.at("transform"), kTransforms)};
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

void to_json(json& j, const ObjectFraming& f) {
  j = {{"name", f.name},
       {"drawn", f.drawn},
       {"fullyVisible", f.fully_visible},
       {"fractionInFrame", f.fraction_in_frame},
       {"imageCoverage", f.image_coverage},
       {"visiblePixels", f.visible_pixels},
       {"behindCamera", f.behind_camera},
       {"partlyBehindCamera", f.partly_behind_camera},
       {"boundingBox", nullptr}};
  if (f.box) j["boundingBox"] = {{"x0", f.box->min.x}, {"y0", f.box->min.y}, {"x1", f.box->max.x}, {"y1", f.box->max.y}};
}

void from_json(const json& j, ObjectFraming& f) {
  j.at("name").get_to(f.name);
  j.at("drawn").get_to(f.drawn);
  j.at("fullyVisible").get_to(f.fully_visible);
  j.at("fractionInFrame").get_to(f.fraction_in_frame);
  j.at("imageCoverage").get_to(f.image_coverage);
  j.at("visiblePixels").get_to(f.visible_pixels);
  j.at("behindCamera").get_to(f.behind_camera);
  j.at("partlyBehindCamera").get_to(f.partly_behind_camera);
  f.box.reset();
  if (const json& b = j.at("boundingBox"); !b.is_null())
    f.box = PixelBox{{b.at("x0").get<double>(), b.at("y0").get<double>()}, {b.at("x1").get<double>(), b.at("y1").get<double>()}};
}

void to_json(json& j, const CameraSummary& c) {
  j = {{"horizontalFov", c.horizontal_fov_degrees}, {"verticalFov", c.vertical_fov_degrees}, {"type", c.type}};
}

void from_json(const json& j, CameraSummary& c) {
  j.at("horizontalFov").get_to(c.horizontal_fov_degrees);
  j.at("verticalFov").get_to(c.vertical_fov_degrees);
  const std::string type = j.at("type");
  if (type != "perspective" && type != "orthographic") throw json::other_error::create(501, "unknown camera type " + type, &j);
  c.type = type == "orthographic" ? scene::Projection::orthographic : scene::Projection::perspective;
}

void to_json(json& j, const SceneReport& r) {
  j = {{"engine", scene::to_string(r.engine)}, {"viewTransform", scene::to_string(r.view_transform)},
       {"width", r.width},                    {"height", r.height},
       {"passes", r.passes},                  {"features", r.features},
       {"framing", r.framing},                {"camera", r.camera},
       {"depth", r.depth},                    {"totalMs", r.total_ms}};
}

void from_json(const json& j, SceneReport& r) {
  r.engine = enum_from_json(j.at("engine"), {scene::Engine::workbench, scene::Engine::eevee});
  r.view_transform = enum_from_json(j.at("viewTransform"), kTransforms);
  j.at("width").get_to(r.width);
  j.at("height").get_to(r.height);
  j.at("passes").get_to(r.passes);
  j.at("features").get_to(r.features);
  j.at("framing").get_to(r.framing);
  j.at("camera").get_to(r.camera);
  j.at("depth").get_to(r.depth);
  j.at("totalMs").get_to(r.total_ms);
}

}  // namespace shadelab::scene_render

namespace shadelab::worker {

void to_json(json& j, const ConstantFrame& c) { j = {{"frame", c.frame}, {"rgba", c.rgba}}; }
void from_json(const json& j, ConstantFrame& c) {
  j.at("frame").get_to(c.frame);
  j.at("rgba").get_to(c.rgba);
}

void to_json(json& j, const RenderTimings& t) {
  j = {{"compile", t.compile_ms}, {"upload", t.upload_ms},     {"firstFrame", t.first_frame_ms},
       {"render", t.render_ms},   {"readback", t.readback_ms}, {"encode", t.encode_ms}};
}

void from_json(const json& j, RenderTimings& t) {
  t = {j.at("compile"), j.at("upload"), j.at("firstFrame"), j.at("render"), j.at("readback"), j.at("encode")};
}

void to_json(json& j, const CompileResult& r) {
  j = {{"warnings", r.warnings}, {"diagnostics", r.diagnostics}, {"attributes", r.attributes}, {"uniforms", r.uniforms},
       {"compileMs", r.compile_ms}};
}

void from_json(const json& j, CompileResult& r) {
  j.at("warnings").get_to(r.warnings);
  j.at("diagnostics").get_to(r.diagnostics);
  j.at("attributes").get_to(r.attributes);
  j.at("uniforms").get_to(r.uniforms);
  j.at("compileMs").get_to(r.compile_ms);
}

void to_json(json& j, const RenderResult& r) {
  j = {{"warnings", r.warnings},          {"diagnostics", r.diagnostics}, {"attributes", r.attributes},
       {"uniforms", r.uniforms},          {"samples", r.samples},         {"constantFrames", r.constant_frames},
       {"timings", r.timings},            {"contentType", r.content_type}};
}

void from_json(const json& j, RenderResult& r) {
  j.at("warnings").get_to(r.warnings);
  j.at("diagnostics").get_to(r.diagnostics);
  j.at("attributes").get_to(r.attributes);
  j.at("uniforms").get_to(r.uniforms);
  j.at("samples").get_to(r.samples);
  j.at("constantFrames").get_to(r.constant_frames);
  j.at("timings").get_to(r.timings);
  j.at("contentType").get_to(r.content_type);
}

void to_json(json& j, const MeshCheckResult& r) {
  j = {{"triangles", r.triangles}, {"normalsFromFile", r.normals_from_file}, {"bounds", {{"min", r.min}, {"max", r.max}}}};
}

void from_json(const json& j, MeshCheckResult& r) {
  j.at("triangles").get_to(r.triangles);
  j.at("normalsFromFile").get_to(r.normals_from_file);
  j.at("bounds").at("min").get_to(r.min);
  j.at("bounds").at("max").get_to(r.max);
}

void to_json(json& j, const SceneResult& r) { j = {{"report", r.report}, {"encodeMs", r.encode_ms}}; }
void from_json(const json& j, SceneResult& r) {
  j.at("report").get_to(r.report);
  j.at("encodeMs").get_to(r.encode_ms);
}

void to_json(json& j, const GradeResult& r) { j = {{"report", r.report}}; }
void from_json(const json& j, GradeResult& r) { j.at("report").get_to(r.report); }

void to_json(json& j, const FramesGradeResult& r) { j = {{"frames", r.frames}, {"code", r.code ? json(*r.code) : json(nullptr)}}; }
void from_json(const json& j, FramesGradeResult& r) {
  j.at("frames").get_to(r.frames);
  r.code = j.at("code").is_null() ? std::nullopt : std::optional<grade::Report>(j.at("code").get<grade::Report>());
}

void to_json(json& j, const ImagesResult& r) { j = {{"verdicts", r.verdicts}}; }
void from_json(const json& j, ImagesResult& r) { j.at("verdicts").get_to(r.verdicts); }

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
