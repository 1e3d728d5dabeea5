// The worker wire (worker/job.h, worker/result.h): every job and every answer, sent and read
// back, is what was sent. Pure CPU; no worker process.
#include <gtest/gtest.h>

#include <cstring>

#include "core/embedded_files.h"
#include "course/course_reader.h"
#include "worker/job.h"
#include "worker/protocol.h"
#include "worker/result.h"

using namespace shadelab;
using nlohmann::json;

namespace {

template <class Result>
Result round_trip(const Result& sent) {
  auto back = worker::result_from<Result>(worker::answer(sent));
  EXPECT_TRUE(back.ok()) << (back ? "" : back.error().message);
  return back ? *back : Result{};
}

scene::SceneDescription example_scene(const std::string& name) {
  const auto text = embedded_file("assets/scenes/" + name + ".json");
  EXPECT_TRUE(text.has_value()) << name;
  auto parsed = scene::parse_scene(json::parse(*text));
  EXPECT_TRUE(parsed.ok()) << name;
  return *parsed;
}

}  // namespace

TEST(WireTest, AGradeJobCarriesItsWholeSpec) {
  worker::Job job;
  job.kind = worker::JobKind::grade;
  job.request.vertex = {"phong_vert.js", "export default `...`;"};
  job.request.uniforms = {{"uLightPosition", {1, 2, 3}}};
  const auto& c = course::builtin_course();
  job.request.page = c.page();
  job.request.angles = {0.0, 19.75};
  job.fit = scene::Bounds{{-1, 0, -1}, {1, 4, 1}};
  job.grade = c.grade_spec(*c.checkpoint("specular")->checkpoint, {});
  job.grade.options.max_score = 7;
  job.grade.heatmap = grade::HeatMap::when_failing;
  job.request.semantics = render::FloatSemantics::ieee;
  job.grade.reference_store = {"/var/cache/shadelab", {.url = "redis://cache:6380/1", .timeout = std::chrono::milliseconds(900),
                                                       .retry_after = std::chrono::milliseconds(3000),
                                                       .time_to_live = std::chrono::seconds(3600), .max_value_bytes = 1u << 20}};
  auto back = worker::job_from_message(worker::to_message(job, "mesh bytes"));
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->kind, worker::JobKind::grade);
  EXPECT_EQ(back->request.vertex.name, "phong_vert.js");
  EXPECT_EQ(back->grade.mistakes.size(), job.grade.mistakes.size());
  EXPECT_EQ(back->grade.probes.size(), job.grade.probes.size());
  EXPECT_EQ(back->grade.probes[0].light_position, job.grade.probes[0].light_position);
  EXPECT_EQ(back->grade.options.max_score, 7);
  EXPECT_EQ(back->grade.heatmap, grade::HeatMap::when_failing);
  EXPECT_EQ(back->request.semantics, render::FloatSemantics::ieee);
  EXPECT_EQ(back->grade.light_position_uniforms, job.grade.light_position_uniforms);
  EXPECT_EQ(back->grade.starter_constants.size(), 1u);
  EXPECT_EQ(back->grade.reference_store.folder, "/var/cache/shadelab");
  EXPECT_EQ(back->grade.reference_store.shared, job.grade.reference_store.shared) << "the operator's Redis deadlines and expiry reach the worker";
  EXPECT_EQ(back->request.page.uniforms.size(), job.request.page.uniforms.size());
  EXPECT_EQ(back->request.page.camera.mesh_translation, job.request.page.camera.mesh_translation);
  EXPECT_EQ(back->request.angles, job.request.angles);
  ASSERT_TRUE(back->fit);
  EXPECT_EQ(back->fit->max, job.fit->max);
  EXPECT_EQ(worker::to_message(*back).header, worker::to_message(job).header);
  EXPECT_FALSE(back->grade.warm);
  // A warm's grade says so; any other grade's job holds no "warm" at all (its bytes as before).
  EXPECT_EQ(worker::to_message(job).header.dump().find("\"warm\":"), std::string::npos);
  job.grade.warm = true;
  auto warm = worker::job_from_message(worker::to_message(job, "mesh bytes"));
  ASSERT_TRUE(warm) << warm.error().message;
  EXPECT_TRUE(warm->grade.warm);
}

TEST(WireTest, ASceneTravelsParsedAndArrivesUnchanged) {
  for (const auto& name : {"two_objects", "dolly_50mm"}) {
    worker::SceneJob job{example_scene(name), {{"my_mesh", "ply", std::string("ply\0bytes", 9)}}};
    job.scene.camera.rotation_degrees = glm::dvec3(90, 0, 0.1);
    const auto message = worker::to_message(job);
    auto back = worker::scene_job_from_message(message);
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_EQ(nlohmann::json(back->scene), nlohmann::json(job.scene)) << name;
    EXPECT_EQ(back->scene.camera.rotation_degrees, job.scene.camera.rotation_degrees);
    ASSERT_EQ(back->meshes.size(), 1u);
    EXPECT_EQ(back->meshes[0].reference, "my_mesh");
    EXPECT_EQ(back->meshes[0].format, "ply");
    EXPECT_EQ(back->meshes[0].bytes, std::string("ply\0bytes", 9));
  }
}

TEST(WireTest, AJobWithoutAKnownKindIsAProtocolError) {
  EXPECT_EQ(worker::job_kind_of({{{"kind", "paint"}}, {}}).error().code, ErrorCode::worker_protocol);
  EXPECT_EQ(worker::job_from_message({{{"kind", "render"}}, {}}).error().code, ErrorCode::worker_protocol);
  worker::Message truncated = worker::to_message(worker::SceneJob{example_scene("two_objects"), {{"m", "obj", "0123456789"}}});
  truncated.payload.resize(4);
  EXPECT_EQ(worker::scene_job_from_message(truncated).error().code, ErrorCode::worker_protocol);
}

TEST(WireTest, ARenderResultKeepsItsReportAndItsFilesAsBytes) {
  worker::RenderResult sent;
  sent.warnings = {"uniform 'x' is not used"};
  sent.diagnostics = {{"fragment", "f.js", 3, 1, "warning", "unused"}};
  sent.attributes = {{"aVertexPosition", "vec4", 1}};
  sent.uniforms = {{"lights[0]", "vec3", 4}};
  sent.samples = 4;
  sent.constant_frames = {{2, {0, 0, 0, 255}}};
  sent.timings = {1, 2, 3, 4, 5, 6};
  sent.content_type = "image/png";
  sent.body = std::string("\x89PNG\0\r\n", 7);
  sent.frames = {{"hw2_a_0.png", "zero"}, {"hw2_a_1.png", std::string(1, '\0')}};
  const auto back = round_trip(sent);
  EXPECT_EQ(back.warnings, sent.warnings);
  EXPECT_EQ(back.diagnostics[0].format(), sent.diagnostics[0].format());
  EXPECT_EQ(back.uniforms[0].array_size, 4);
  EXPECT_EQ(back.samples, 4);
  EXPECT_EQ(back.constant_frames[0].frame, 2);
  EXPECT_EQ(back.constant_frames[0].rgba[3], 255);
  EXPECT_EQ(back.timings.encode_ms, 6);
  EXPECT_EQ(back.body, sent.body);
  ASSERT_EQ(back.frames.size(), 2u);
  EXPECT_EQ(back.frames[1].name, "hw2_a_1.png");
  EXPECT_EQ(back.frames[1].bytes, sent.frames[1].bytes);
}

TEST(WireTest, CompileMeshGradeAndSceneResultsRoundTrip) {
  const auto compiled = round_trip(worker::CompileResult{{"w"}, {}, {{"a", "vec4", 1}}, {{"u", "mat4", 1}}, 12.5});
  EXPECT_EQ(compiled.compile_ms, 12.5);
  EXPECT_EQ(compiled.uniforms[0].type, "mat4");

  const auto mesh = round_trip(worker::MeshCheckResult{1234, true, {-1, -2, -3}, {1, 2, 3.5}});
  EXPECT_EQ(mesh.triangles, 1234u);
  EXPECT_TRUE(mesh.normals_from_file);
  EXPECT_EQ(mesh.max[2], 3.5);

  grade::Report report = grade::failed_submission(make_error(ErrorCode::render_timeout, "took too long"), "specular", 3);
  report.frames.push_back({{}, "behind"});
  report.frames[0].grade.metrics.psnr = 31.5;
  report.frames[0].grade.non_finite.nan = 17;
  const auto graded = round_trip(worker::GradeResult{report, "heat"});
  EXPECT_EQ(grade::to_json(graded.report), grade::to_json(report));
  EXPECT_EQ(graded.heatmap_png, "heat");

  worker::SceneResult scene;
  scene.report.width = 640;
  scene.report.engine = scene::Engine::workbench;
  scene.report.passes = {{1.5, scene_render::ShadowDetail{2, 1024, 16}}, {70, scene_render::MainDetail{2, true, 4, "ENGINE_EEVEE"}},
                         {0.5, scene_render::ViewDetail{scene::ViewTransform::filmic}}, {3, scene_render::FramingDetail{1}}};
  scene.report.framing = {{"Suzanne", true, scene_render::PixelBox{{1, 2}, {3, 4}}, false, false, true, 0.75, 0.1, 999}};
  scene.report.camera = {39.6, 30.3, scene::Projection::orthographic};
  scene.png = "png";
  const auto back = round_trip(scene);
  EXPECT_EQ(nlohmann::json(back.report), nlohmann::json(scene.report));
  EXPECT_EQ(back.report.passes[1].name(), "main");
  EXPECT_EQ(back.report.detail<scene_render::FramingDetail>()->guard_band_renders, 1);
  EXPECT_EQ(back.png, "png");
}

namespace shadelab::worker {
namespace {

// The shared store keeps messages as one string: the socket's layout, checked as strictly.
TEST(WireTest, AMessageKeptAsBytesComesBackWholeOrNotAtAll) {
  const Message m{{{"etag", "\"abc\""}, {"n", 3}}, std::string("\x89PNG\0\1\2", 7)};
  const std::string bytes = encode_message(m);
  auto back = decode_message(bytes);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->header, m.header);
  EXPECT_EQ(back->payload, m.payload);
  for (size_t cut : {size_t{0}, size_t{5}, size_t{12}, bytes.size() - 1}) EXPECT_FALSE(decode_message(bytes.substr(0, cut))) << cut;
  EXPECT_FALSE(decode_message(bytes + "x"));
  std::string garbled = bytes;
  garbled[12] = '!';  // the header is no longer JSON
  EXPECT_FALSE(decode_message(garbled));
}

// Readers convert with get<int>(), which casts a float unchecked: 1e20 read into a frame count
// would be undefined behaviour, so such a header is malformed before any reader sees it. Deep
// nesting (dump() and == recurse) is refused too; a message ShadeLab writes nests 6 levels.
TEST(WireTest, AHeaderWithAnOutOfRangeNumberOrDeepNestingIsMalformed) {
  const auto header_only = [](const std::string& header) {
    std::string bytes(12, '\0');
    const auto size = static_cast<std::uint32_t>(header.size());
    std::memcpy(bytes.data(), &size, 4);
    return bytes + header;
  };
  EXPECT_TRUE(decode_message(header_only(R"({"ok":true,"result":{"samples":4.5e8,"ms":-2e9}})")));
  EXPECT_FALSE(decode_message(header_only(R"({"ok":true,"result":{"samples":1e20}})")));
  EXPECT_FALSE(decode_message(header_only(R"({"result":[-3e9]})")));
  const auto nested = [](int depth) {
    std::string text = "{}";
    for (int i = 1; i < depth; ++i) text = R"({"a":)" + text + "}";
    return text;
  };
  EXPECT_TRUE(decode_message(header_only(nested(20))));
  EXPECT_FALSE(decode_message(header_only(nested(40))));
  EXPECT_FALSE(decode_message(header_only("[1,2]"))) << "a header is an object";
}

// json::value() throws when the key holds another type: every reader of a worker's answer reads
// a field of the wrong type as a malformed answer instead (CI's fuzz of wire_message found
// {"ok":{...}} ending the process).
TEST(WireTest, AnAnswerWithFieldsOfTheWrongTypeIsAProtocolErrorNotAnException) {
  for (const json& header : {json{{"ok", json::object()}}, json{{"ok", "true"}}, json{{"ok", false}, {"error", {{"code", 7}}}},
                             json{{"ok", false}, {"error", "compile_failed"}}}) {
    auto result = result_from<CompileResult>(Message{header, {}});
    ASSERT_FALSE(result) << header.dump();
    EXPECT_EQ(result.error().code, ErrorCode::worker_protocol) << header.dump();
  }
  EXPECT_EQ(header_text(json{{"event", 3}}, "event", "none"), "none");
  EXPECT_FALSE(header_flag(json{{"ok", 1}}, "ok"));
  EXPECT_TRUE(header_flag(json{{"ok", true}}, "ok"));
}

}  // namespace
}  // namespace shadelab::worker
