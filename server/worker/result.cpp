#include "worker/result.h"

namespace shadelab::worker {

using nlohmann::json;
using scene_render::PassDetail;

namespace {

Message ok(json result, const std::vector<PayloadPartView>& files = {}) {
  Message m;
  json index = pack_parts(files, m.payload);
  m.header = {{"ok", true}, {"result", std::move(result)}, {"files", std::move(index)}};
  return m;
}

std::vector<Diagnostic> diagnostics_from(const json& j) {
  std::vector<Diagnostic> out;
  for (const auto& d : j) out.push_back(grade::diagnostic_from_json(d));
  return out;
}

std::vector<render::VariableInfo> variables_from(const json& j) {
  std::vector<render::VariableInfo> out;
  for (const auto& v : j) out.push_back({v.at("name"), v.at("type"), v.at("arraySize")});
  return out;
}

RenderTimings timings_from(const json& j) {
  return {j.at("compile"), j.at("upload"), j.at("firstFrame"), j.at("render"), j.at("readback"), j.at("encode")};
}

template <class E>
E enum_from(const json& j, std::initializer_list<E> values) {
  for (const E v : values)
    if (j == scene::to_string(v)) return v;
  throw json::other_error::create(501, "unknown value " + j.dump(), &j);
}

scene_render::ObjectFraming framing_from(const json& j) {
  scene_render::ObjectFraming f;
  f.name = j.at("name");
  f.drawn = j.at("drawn");
  f.fully_visible = j.at("fullyVisible");
  f.fraction_in_frame = j.at("fractionInFrame");
  f.image_coverage = j.at("imageCoverage");
  f.visible_pixels = j.at("visiblePixels");
  f.behind_camera = j.at("behindCamera");
  f.partly_behind_camera = j.at("partlyBehindCamera");
  if (const json& b = j.at("boundingBox"); !b.is_null())
    f.box = scene_render::PixelBox{{b.at("x0").get<double>(), b.at("y0").get<double>()},
                                   {b.at("x1").get<double>(), b.at("y1").get<double>()}};
  return f;
}

PassDetail detail_from(const std::string& name, const json& d) {
  using namespace scene_render;
  if (name == "setup") return SetupDetail{d.at("objects")};
  if (name == "shadow") return ShadowDetail{d.at("views"), d.at("size"), d.at("filterTaps")};
  if (name == "reflection") return ReflectionDetail{d.at("size"), d.at("levels")};
  if (name == "main") return MainDetail{d.at("objects"), d.at("ground"), d.at("samples"), d.at("shaderVariant")};
  if (name == "view") return ViewDetail{enum_from(d.at("transform"), {scene::ViewTransform::standard, scene::ViewTransform::filmic})};
  if (name == "readback") return ReadbackDetail{};
  if (name == "framing") return FramingDetail{d.at("guardBandRenders")};
  throw json::other_error::create(501, "unknown pass '" + name + "'", &d);
}

scene_render::SceneReport scene_report_from(const json& j) {
  scene_render::SceneReport r;
  r.engine = enum_from(j.at("engine"), {scene::Engine::workbench, scene::Engine::eevee});
  r.view_transform = enum_from(j.at("viewTransform"), {scene::ViewTransform::standard, scene::ViewTransform::filmic});
  r.width = j.at("width");
  r.height = j.at("height");
  for (const auto& p : j.at("passes")) r.passes.push_back({p.at("ms"), detail_from(p.at("name"), p.at("detail"))});
  r.features = j.at("features").get<std::vector<std::string>>();
  for (const auto& f : j.at("framing")) r.framing.push_back(framing_from(f));
  const json& c = j.at("camera");
  r.camera = {c.at("horizontalFov"), c.at("verticalFov"),
              c.at("type") == "orthographic" ? scene::Projection::orthographic : scene::Projection::perspective};
  r.depth = j.at("depth");
  r.total_ms = j.at("totalMs");
  return r;
}

// The file of an answer of that name, moved out; empty when there is none.
std::string take_file(std::vector<PayloadPart>& files, std::string_view name) {
  for (auto& f : files)
    if (f.name == name) return std::move(f.bytes);
  return {};
}

// Reads one result type off its JSON and files; throws nlohmann::json::exception when malformed.
template <class Result>
Result read(const json& j, std::vector<PayloadPart>& files);

template <>
CompileResult read(const json& j, std::vector<PayloadPart>&) {
  return {j.at("warnings").get<std::vector<std::string>>(), diagnostics_from(j.at("diagnostics")),
          variables_from(j.at("attributes")), variables_from(j.at("uniforms")), j.at("compileMs")};
}

template <>
RenderResult read(const json& j, std::vector<PayloadPart>& files) {
  RenderResult r;
  r.warnings = j.at("warnings").get<std::vector<std::string>>();
  r.diagnostics = diagnostics_from(j.at("diagnostics"));
  r.attributes = variables_from(j.at("attributes"));
  r.uniforms = variables_from(j.at("uniforms"));
  r.samples = j.at("samples");
  for (const auto& c : j.at("constantFrames")) r.constant_frames.push_back({c.at("frame"), c.at("rgba").get<std::array<int, 4>>()});
  r.timings = timings_from(j.at("timings"));
  r.content_type = j.at("contentType");
  for (auto& f : files) {
    if (f.name == "body") r.body = std::move(f.bytes);
    else r.frames.push_back({std::move(f.name), std::move(f.bytes)});
  }
  return r;
}

template <>
MeshCheckResult read(const json& j, std::vector<PayloadPart>&) {
  return {j.at("triangles"), j.at("normalsFromFile"), j.at("bounds").at("min").get<std::array<double, 3>>(),
          j.at("bounds").at("max").get<std::array<double, 3>>()};
}

template <>
SceneResult read(const json& j, std::vector<PayloadPart>& files) {
  return {scene_report_from(j.at("report")), j.at("encodeMs"), take_file(files, "image.png")};
}

grade::Report report_at(const json& j) {
  auto report = grade::report_from_json(j);
  if (!report) throw json::other_error::create(501, report.error().message, &j);
  return std::move(*report);
}

template <>
GradeResult read(const json& j, std::vector<PayloadPart>& files) {
  return {report_at(j.at("report")), take_file(files, "heatmap.png")};
}

template <>
FramesGradeResult read(const json& j, std::vector<PayloadPart>& files) {
  FramesGradeResult r{report_at(j.at("frames")), {}, take_file(files, "heatmap.png")};
  if (const json& code = j.at("code"); !code.is_null()) r.code = report_at(code);
  return r;
}

}  // namespace

json to_json(const Error& e) {
  return {{"code", to_string(e.code)}, {"message", e.message}, {"diagnostics", diagnostics_json(e.diagnostics)},
          {"driverLog", e.driver_log}};
}

Error error_from_json(const json& j) {
  Error e{ErrorCode::worker_protocol, "a render worker reported an error it did not name", {}, {}};
  if (!j.is_object()) return e;
  const auto code = error_code_named(text_field(j, "code"));
  if (!code) {
    e.message = "a render worker reported an unknown error code " + (j.contains("code") ? j["code"] : json("")).dump();
    return e;
  }
  e.code = *code;
  // The worker runs student code: what it sends is read, not trusted (a missing or non-string
  // message is the code's title, never an empty detail or an exception).
  const auto text = [&j](const char* key) { return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : std::string(); };
  e.message = text("message");
  if (e.message.empty()) e.message = std::string(info(e.code).title);
  e.driver_log = text("driverLog");
  if (j.contains("diagnostics") && j["diagnostics"].is_array()) e.diagnostics = diagnostics_from(j["diagnostics"]);
  return e;
}

json diagnostics_json(const std::vector<Diagnostic>& ds) {
  json out = json::array();
  for (const auto& d : ds) out.push_back(grade::to_json(d));
  return out;
}

json variables_json(const std::vector<render::VariableInfo>& vs) {
  json out = json::array();
  for (const auto& v : vs) out.push_back(to_json(v));
  return out;
}

json to_json(const render::VariableInfo& v) { return {{"name", v.name}, {"type", v.type}, {"arraySize", v.array_size}}; }

json to_json(const RenderTimings& t) {
  return {{"compile", t.compile_ms}, {"upload", t.upload_ms},     {"firstFrame", t.first_frame_ms},
          {"render", t.render_ms},   {"readback", t.readback_ms}, {"encode", t.encode_ms}};
}

json to_json(const MeshCheckResult& r) {
  return {{"triangles", r.triangles}, {"normalsFromFile", r.normals_from_file}, {"bounds", {{"min", r.min}, {"max", r.max}}}};
}

json to_json(const scene_render::ObjectFraming& f) {
  json j = {{"name", f.name},
            {"drawn", f.drawn},
            {"fullyVisible", f.fully_visible},
            {"fractionInFrame", f.fraction_in_frame},
            {"imageCoverage", f.image_coverage},
            {"visiblePixels", f.visible_pixels},
            {"behindCamera", f.behind_camera},
            {"partlyBehindCamera", f.partly_behind_camera},
            {"boundingBox", nullptr}};
  if (f.box) j["boundingBox"] = {{"x0", f.box->min.x}, {"y0", f.box->min.y}, {"x1", f.box->max.x}, {"y1", f.box->max.y}};
  return j;
}

json to_json(const PassDetail& detail) {
  using namespace scene_render;
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

json to_json(const scene_render::SceneReport& r) {
  json passes = json::array(), framing = json::array();
  for (const auto& p : r.passes) passes.push_back({{"name", p.name()}, {"ms", p.ms}, {"detail", to_json(p.detail)}});
  for (const auto& f : r.framing) framing.push_back(to_json(f));
  return {{"engine", scene::to_string(r.engine)},
          {"viewTransform", scene::to_string(r.view_transform)},
          {"width", r.width},
          {"height", r.height},
          {"passes", passes},
          {"features", r.features},
          {"framing", framing},
          {"camera",
           {{"horizontalFov", r.camera.horizontal_fov_degrees},
            {"verticalFov", r.camera.vertical_fov_degrees},
            {"type", r.camera.type == scene::Projection::perspective ? "perspective" : "orthographic"}}},
          {"depth", r.depth},
          {"totalMs", r.total_ms}};
}

Message answer(const CompileResult& r) {
  return ok({{"warnings", r.warnings}, {"diagnostics", diagnostics_json(r.diagnostics)}, {"attributes", variables_json(r.attributes)},
             {"uniforms", variables_json(r.uniforms)}, {"compileMs", r.compile_ms}});
}

Message answer(const RenderResult& r) {
  json constant = json::array();
  for (const auto& c : r.constant_frames) constant.push_back({{"frame", c.frame}, {"rgba", c.rgba}});
  std::vector<PayloadPartView> files{{"body", r.body}};
  for (const auto& f : r.frames) files.push_back({f.name, f.bytes});
  return ok({{"warnings", r.warnings},
             {"diagnostics", diagnostics_json(r.diagnostics)},
             {"attributes", variables_json(r.attributes)},
             {"uniforms", variables_json(r.uniforms)},
             {"samples", r.samples},
             {"constantFrames", constant},
             {"timings", to_json(r.timings)},
             {"contentType", r.content_type}},
            files);
}

Message answer(const MeshCheckResult& r) { return ok(to_json(r)); }

Message answer(const SceneResult& r) {
  return ok({{"report", to_json(r.report)}, {"encodeMs", r.encode_ms}}, {{"image.png", r.png}});
}

Message answer(const GradeResult& r) {
  std::vector<PayloadPartView> files;
  if (!r.heatmap_png.empty()) files.push_back({"heatmap.png", r.heatmap_png});
  return ok({{"report", grade::to_json(r.report)}}, files);
}

Message answer(const FramesGradeResult& r) {
  std::vector<PayloadPartView> files;
  if (!r.heatmap_png.empty()) files.push_back({"heatmap.png", r.heatmap_png});
  return ok({{"frames", grade::to_json(r.frames)}, {"code", r.code ? grade::to_json(*r.code) : json(nullptr)}}, files);
}

Message answer(const Error& e) { return {{{"ok", false}, {"error", to_json(e)}}, {}}; }

template <class Result>
Expected<Result> result_from(const Message& m) {
  if (!m.header.is_object()) return make_error(ErrorCode::worker_protocol, "a render worker's answer is not an object");
  if (!flag_field(m.header, "ok")) return error_from_json(m.header.contains("error") ? m.header["error"] : json::object());
  try {
    auto files = unpack_parts(m.header.at("files"), m.payload);
    if (!files) return files.take_error();
    return read<Result>(m.header.at("result"), *files);
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

}  // namespace shadelab::worker
