// http/api_request.cpp: what a client sent, to a validated worker job. Pure CPU; no server.
#include <gtest/gtest.h>

#include "http/api_request.h"
#include "http/grade_request.h"
#include "road/code_request.h"
#include "course/course_reader.h"

using namespace shadelab;
using nlohmann::json;

namespace {

const char* kVertex = "#version 300 es\nin vec4 aVertexPosition;\nvoid main() { gl_Position = aVertexPosition; }\n";
const char* kFragment = "#version 300 es\nprecision highp float;\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";

Expected<http::ParsedJob> parse(const json& fields, worker::JobKind kind = worker::JobKind::render) {
  auto raw = http::from_json_body(fields.dump());
  if (!raw) return raw.take_error();
  return http::parse_job(*raw, kind, http::Limits{}, course::builtin_course());
}

std::string error_of(const json& fields) {
  auto parsed = parse(fields);
  return parsed ? std::string("(parsed)") : parsed.error().message;
}

}  // namespace

TEST(ApiRequestTest, ABodyMustBeAJsonObject) {
  EXPECT_EQ(http::from_json_body("{").error().message, "the request body is not valid JSON");
  EXPECT_EQ(http::from_json_body("[1]").error().message, "the request body must be a JSON object");
  EXPECT_TRUE(http::from_json_body("{}"));
}

TEST(ApiRequestTest, APresetExpandsToItsShadersAndNamesTheFrames) {
  auto parsed = parse({{"preset", "specular"}, {"mesh", "teapot"}, {"width", 320}, {"height", 240}, {"frames", 3}});
  ASSERT_TRUE(parsed) << parsed.error().message;
  const auto& c = course::builtin_course();
  EXPECT_EQ(parsed->job.request.fragment.text, c.preset("specular")->fragment.text);
  EXPECT_EQ(parsed->job.prefix, "specular");
  EXPECT_EQ(parsed->job.mesh, c.mesh("teapot")->id);
  EXPECT_EQ(parsed->job.mesh_embedded, c.mesh("teapot")->id);
  EXPECT_EQ(parsed->job.frame_name, c.frame_name);
  EXPECT_EQ(parsed->job.request.width, 320);
  EXPECT_EQ(parsed->job.request.frames, 3);
  EXPECT_TRUE(parsed->warnings.empty());
}

TEST(ApiRequestTest, EveryFieldIsTypeCheckedWithItsName) {
  EXPECT_EQ(error_of({{"preset", "smooth"}, {"width", "wide"}}), "'width' must be a whole number; got \"wide\"");
  EXPECT_EQ(error_of({{"preset", "smooth"}, {"width", 1.5}}), "'width' must be a whole number; got 1.5");
  EXPECT_EQ(error_of({{"preset", "smooth"}, {"fit", 1}}), "'fit' must be true or false");
  EXPECT_EQ(error_of({{"preset", "smooth"}, {"output", "gif"}}), "'output' must be grid, frames or json");
  EXPECT_EQ(error_of({{"preset", "smooth"}, {"prefix", "../etc"}}), "'prefix' may hold only letters, digits, '_' and '-' (at most 64)");
  EXPECT_EQ(error_of({{"preset", "smooth"}, {"uniforms", {{"uColor", "red"}}}}), "uniform 'uColor' must be numbers or booleans; got \"red\"");
  EXPECT_EQ(error_of({{"preset", "smooth"}, {"vertex", kVertex}}), "give either 'preset' or 'vertex' and 'fragment', not both");
  EXPECT_EQ(error_of(json::object()), "give 'vertex' and 'fragment' shader sources, or a 'preset'");
  EXPECT_EQ(parse({{"preset", "nope"}}).error().code, ErrorCode::unknown_preset);
  EXPECT_EQ(parse({{"preset", "smooth"}, {"frames", 0}}).error().code, ErrorCode::invalid_argument);
}

TEST(ApiRequestTest, SourceProblemsAreAnsweredBeforeAnyWorker) {
  // A GLSL ES 1.00 fragment shader (no #version) with an ES 3.00 vertex shader: WebGL 2 does not link them.
  EXPECT_EQ(parse({{"vertex", kVertex}, {"fragment", "precision highp float;\nvoid main() {}\n"}}).error().code, ErrorCode::link_failed);
  EXPECT_EQ(parse({{"vertex", kVertex}, {"fragment", "#version 310 es\nvoid main() {}\n"}}).error().code, ErrorCode::missing_version);
  http::RawRequest multipart;  // as a multipart upload brings it: bytes, not JSON text
  multipart.fields = {{"vertex", kVertex}};
  multipart.files["fragment"] = {"phong_frag.js", "#version 300 es\n\xff\xfe"};
  EXPECT_EQ(http::parse_job(multipart, worker::JobKind::render, http::Limits{}, course::builtin_course()).error().code, ErrorCode::shader_source_invalid);
  EXPECT_EQ(parse({{"vertex", kVertex}, {"fragment", std::string(70 * 1024, ' ')}}).error().code, ErrorCode::payload_too_large);
}

TEST(ApiRequestTest, UnknownFieldsAreWarnedAboutAndIgnored) {
  auto parsed = parse({{"vertex", kVertex}, {"fragment", kFragment}, {"colour", "red"}});
  ASSERT_TRUE(parsed) << parsed.error().message;
  ASSERT_EQ(parsed->warnings.size(), 1u);
  EXPECT_EQ(parsed->warnings[0], "field 'colour' is not part of the API and was ignored");
}

TEST(ApiRequestTest, FormFieldsAreTypedAsTheirJsonLiteralsButShaderTextStaysText) {
  const std::multimap<std::string, std::string> fields = {{"width", "64"}, {"fit", "true"}, {"uniforms", R"({"uDiffuseColor": [1, 0, 0, 1]})"},
                                                          {"prefix", "123"}, {"vertex", "1"}};
  const auto raw = http::from_form(fields, {});
  EXPECT_EQ(raw.fields["width"], 64);
  EXPECT_EQ(raw.fields["fit"], true);
  EXPECT_TRUE(raw.fields["uniforms"].is_object());
  EXPECT_EQ(raw.fields["prefix"], "123");
  EXPECT_EQ(raw.fields["vertex"], "1");
}

TEST(ApiRequestTest, AnUploadedMeshIsNamedByItsContentAndFormat) {
  http::RawRequest raw;
  raw.fields = {{"preset", "smooth"}};
  raw.files["mesh"] = {"Model.GLB", "glTF-bytes"};
  auto parsed = http::parse_job(raw, worker::JobKind::render, http::Limits{}, course::builtin_course());
  ASSERT_TRUE(parsed) << parsed.error().message;
  EXPECT_EQ(parsed->job.mesh, http::mesh_id("glTF-bytes"));
  EXPECT_EQ(parsed->job.mesh_format, "GLB");
  ASSERT_TRUE(parsed->mesh_upload);
  EXPECT_EQ(parsed->mesh_upload->bytes, "glTF-bytes");
  EXPECT_EQ(parsed->mesh_upload->id, parsed->job.mesh);
  EXPECT_EQ(http::mesh_id("glTF-bytes"), http::mesh_id("glTF-bytes"));
  EXPECT_NE(http::mesh_id("glTF-bytes"), http::mesh_id("glTF-bytez"));
}

// A parsed request, sent to a worker and read back there, is the same request.
TEST(ApiRequestTest, AParsedJobSurvivesTheWorkerWire) {
  auto parsed = parse({{"vertex", kVertex}, {"fragment", kFragment}, {"width", 96}, {"height", 72}, {"frames", 4},
                       {"degreesPerFrame", 12.5}, {"msaa", 0}, {"uniforms", {{"uDiffuseColor", {0.1, 0.2, 0.3, 1}}}},
                       {"mesh", "teapot"}, {"fit", true}, {"prefix", "mine"}, {"output", "frames"}, {"format", "exr"}});
  ASSERT_TRUE(parsed) << parsed.error().message;
  auto back = worker::job_from_message(worker::to_message(parsed->job));
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(worker::to_message(*back).header, worker::to_message(parsed->job).header);
  EXPECT_EQ(back->request.pixel_type, image::PixelType::f32);
  EXPECT_EQ(back->request.uniforms[0].values[1], 0.2);
}

// A grade's fields read over HTTP (parse_code_grade), made a job by the road (road::code_submission).
TEST(ApiRequestTest, AGradeNamesACheckpointOrACustomReferenceAndItsTolerances) {
  struct Built {
    std::string result_format;
    grade::GradeSpec spec;
  };
  const auto grade = [](json fields) -> Expected<Built> {
    fields["vertex"] = kVertex;
    fields["fragment"] = kFragment;
    auto parsed = http::parse_code_grade(*http::from_json_body(fields.dump()), http::Limits{});
    if (!parsed) return parsed.take_error();
    auto built = road::code_submission(course::builtin_course(), std::move(parsed->request), course::Viewer{}, render::RenderLimits{});
    if (!built) return built.take_error();
    return Built{parsed->result_format, std::move(built->submission.spec)};
  };
  auto specular = grade({{"reference", "specular"}, {"threshold", 0.05}, {"format", "gradescope"}});
  ASSERT_TRUE(specular) << specular.error().message;
  EXPECT_EQ(specular->result_format, "gradescope");
  EXPECT_EQ(specular->spec.reference_name, "specular");
  EXPECT_FALSE(specular->spec.mistakes.empty());
  EXPECT_EQ(specular->spec.options.compare.threshold, 0.05);
  EXPECT_FALSE(grade(json::object()));
  EXPECT_FALSE(grade({{"reference", "specular"}, {"referenceVertex", kVertex}}));
  EXPECT_EQ(grade({{"reference", "shiny"}}).error().code, ErrorCode::unknown_preset);
  // A warm-up preset is not a deliverable, and the message says so.
  const auto smooth = grade({{"reference", "smooth"}});
  ASSERT_FALSE(smooth);
  EXPECT_NE(smooth.error().message.find("'smooth' is a preset (a warm-up step), not a deliverable"), std::string::npos);
  EXPECT_EQ(grade({{"reference", "normals"}, {"threshold", 2}}).error().code, ErrorCode::invalid_argument);
  EXPECT_EQ(grade({{"reference", "normals"}, {"spatialTolerance", "yes"}}).error().message, "'spatialTolerance' must be true or false");
  auto custom = grade({{"referenceVertex", kVertex}, {"referenceFragment", kFragment}});
  ASSERT_TRUE(custom) << custom.error().message;
  EXPECT_EQ(custom->spec.reference_name, "custom");
  EXPECT_EQ(custom->spec.reference_fragment.text, kFragment);
}
