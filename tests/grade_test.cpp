// Grading through the real server and workers: each checkpoint against itself, and the mistakes
// students make, each recognised with the right message.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <set>

#include <nlohmann/json.hpp>

#include "core/base64.h"
#include "core/lru_cache.h"
#include "grade/diagnosis.h"
#include "grade/judge_code.h"
#include "grade/reference_cache.h"
#include "grade/starter_constants.h"
#include "scene/mesh.h"
#include "support/http_fixture.h"
#include "support/openapi_check.h"
#include "support/test_support.h"

using nlohmann::json;
using namespace shadelab;

namespace {

class GradeTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { server_ = new testkit::RunningService(testkit::test_config()); }
  static void TearDownTestSuite() { delete server_; }
  void SetUp() override { ASSERT_TRUE(server_->ok()) << server_->failure; }

  // A submission: a preset's shaders with one edit applied to the fragment (or vertex) shader.
  static json submission(const std::string& preset, const std::string& from = "", const std::string& to = "",
                         bool vertex = false) {
    auto p = *testkit::course().preset(preset);
    auto& file = vertex ? p.vertex.text : p.fragment.text;
    if (!from.empty()) {
      const auto at = file.find(from);
      EXPECT_NE(at, std::string::npos) << from;
      file.replace(at, from.size(), to);
    }
    return {{"vertex", p.vertex.text}, {"fragment", p.fragment.text}, {"vertexName", "phong_vert.js"},
            {"fragmentName", "phong_frag.js"}, {"width", 160}, {"height", 120}};
  }
  static json grade(json job, const std::string& reference) {
    job["reference"] = reference;
    auto r = server_->client().Post("/api/grade", job.dump(), "application/json");
    if (!r) {
      ADD_FAILURE() << "no response from /api/grade";
      return json::object();
    }
    EXPECT_EQ(r->status, 200) << r->body;
    return json::parse(r->body);
  }
  static testkit::RunningService* server_;
};
testkit::RunningService* GradeTest::server_ = nullptr;

TEST_F(GradeTest, EachCheckpointGradedAgainstItselfScoresFullMarks) {
  for (const auto& checkpoint : testkit::course().checkpoints) {
    const std::string c = checkpoint.name;
    const json r = grade(submission(checkpoint.reference), c);
    EXPECT_TRUE(r["pass"]) << c << ": " << r.dump();
    EXPECT_EQ(r["score"], 1.0) << c;
    EXPECT_EQ(r["frames"].size(), 9u * (1 + checkpoint.probes.size())) << c;  // the page's light, then each probe light
    EXPECT_TRUE(r["frames"][0]["identical"]) << c;
    EXPECT_TRUE(r["frames"][0]["psnr"].is_null()) << c;  // identical: no infinite PSNR in the JSON
    EXPECT_FALSE(r["heatmap"].get<std::string>().empty());
  }
}

TEST_F(GradeTest, TheFlatStarterHandedInAsNormalsIsRecognised) {
  const json r = grade(submission("starter"), "normals");
  EXPECT_FALSE(r["pass"]);
  EXPECT_EQ(r["diagnosis"], "flat_shading") << r.dump();
  EXPECT_NE(r["messages"][0].get<std::string>().find("flat"), std::string::npos);
}

TEST_F(GradeTest, MissingSpecularIsRecognised) {
  const json r = grade(submission("diffuse"), "specular");
  EXPECT_FALSE(r["pass"]);
  EXPECT_EQ(r["score"], 0.0);
  EXPECT_EQ(r["diagnosis"], "missing_specular") << r.dump();
  EXPECT_NE(r["messages"][0].get<std::string>().find("specular highlight missing"), std::string::npos);
}

// Written the way a student would, not as the catalogue's own edit: the guard left out is put back
// at the student's line (repair/left_out_edits.h), confirmed by a render, so the catalogue that
// names it without a line (`unguarded_specular`) is not needed; the words say what the guard is.
TEST_F(GradeTest, SpecularWithoutTheNdotLGuardIsRecognised) {
  const json r = grade(submission("specular", "    if (NdotL > 0.0) {", "    {"), "specular");
  EXPECT_FALSE(r["pass"]);
  const json& found = r["repairSearch"]["found"];
  EXPECT_EQ(found["kind"], "guard_added") << r.dump();
  EXPECT_EQ(found["label"], "the highlight not guarded by N.L > 0") << r.dump();
  const std::string text = found["text"];
  EXPECT_NE(text.find("faces away from the light"), std::string::npos) << text;
  EXPECT_NE(text.find("only where `NdotL > 0.0`"), std::string::npos) << text;
}

// The page's light is white, so a term that leaves uLightColor out is right under it; under the
// coloured probe light it is not, for the specular term and for the diffuse one.
TEST_F(GradeTest, ATermWithoutTheLightsColourFailsUnderTheColouredLight) {
  for (const auto& [reference, with, without] : {std::tuple{"specular", "uSpecularColor * uLightColor * pow(", "uSpecularColor * pow("},
                                                 std::tuple{"diffuse", "uDiffuseColor * uLightColor * max(", "uDiffuseColor * max("}}) {
    SCOPED_TRACE(reference);
    const json r = grade(submission(reference, with, without), reference);
    EXPECT_FALSE(r["pass"]) << r.dump().substr(0, 600);
    EXPECT_TRUE(r["messages"][0].get<std::string>().starts_with(
        "right under the page's light, not under the probe light coloured_light (9 of 9 frames differ), which checks that the light's colour (uLightColor) multiplies"))
        << r["messages"];
    ASSERT_FALSE(r["frames"].empty());
    for (const auto& f : r["frames"]) {
      const std::string light = f["light"];
      if (light == "coloured_light") {
        EXPECT_FALSE(f["pass"]) << f.dump();
      } else {
        EXPECT_TRUE(f["pass"]) << light << " " << f.dump();
      }
    }
  }
}

TEST_F(GradeTest, SwappedChannelsAreRecognised) {
  const json r = grade(submission("specular", "    fragColor = color;", "    fragColor = color.bgra;"), "specular");
  EXPECT_FALSE(r["pass"]);
  EXPECT_EQ(r["diagnosis"], "swapped_channels") << r.dump();
  EXPECT_NE(r["messages"][0].get<std::string>().find("(B, G, R)"), std::string::npos);
}

// A pair written the way a student of the course writes it: the starters as distributed (vec3
// varyings, `specularAlpha = 6.0`, the TODOs done in their own words), not the presets' text.
json student_pair(const std::string& alpha, bool specular) {
  const std::string vertex = R"(export default `#version 300 es
precision highp float;

in vec4 aVertexPosition;
in vec4 aVertexNormal;

uniform mat4 uMeshToWorldMatrix;
uniform mat4 uMeshToWorldRotMatrix;
uniform mat4 uWorldToClipSpaceMatrix;

out vec3 vPosition;
out vec3 vNormal;

void main(void) {
    vPosition = (uMeshToWorldMatrix * aVertexPosition).xyz;
    vNormal = (uMeshToWorldRotMatrix * aVertexNormal).xyz;
    gl_Position = uWorldToClipSpaceMatrix * uMeshToWorldMatrix * aVertexPosition;
}
`;
)";
  const std::string fragment = R"(export default `#version 300 es
precision highp float;

uniform vec4 uAmbientColor;
uniform vec4 uDiffuseColor;
uniform vec4 uSpecularColor;
uniform vec4 uLightColor;
uniform vec3 uLightPosition;

in vec3 vPosition;
in vec3 vNormal;
out vec4 fragColor;

void main(void) {
    float specularAlpha = )" + alpha + R"(;

    // TODO: diffuse
    vec3 n = normalize(vNormal);
    vec3 toLight = normalize(uLightPosition - vPosition);
    float lambert = dot(n, toLight);
    vec4 diffuse = uDiffuseColor * uLightColor * max(0.0, lambert);

    // TODO: specular, only on the lit side
    vec4 specular = vec4(0.0);
    if ()" + std::string(specular ? "lambert > 0.0" : "false") + R"() {
        vec3 toEye = normalize(-vPosition);
        vec3 mirrored = reflect(-toLight, n);
        specular = uSpecularColor * uLightColor * pow(max(0.0, dot(toEye, mirrored)), specularAlpha);
    }
    fragColor = uAmbientColor + diffuse + specular;
}
`;
)";
  return {{"vertex", vertex}, {"fragment", fragment}, {"vertexName", "phong_vert.js"}, {"fragmentName", "phong_frag.js"},
          {"width", 160}, {"height", 160}};
}

TEST_F(GradeTest, APairWrittenOnTheCoursesStarterPassesEachDeliverable) {
  const json normals = grade(submission("normals"), "normals");
  EXPECT_TRUE(normals["pass"]) << normals.dump();
  const json diffuse = grade(student_pair("6.0", false), "diffuse");
  EXPECT_TRUE(diffuse["pass"]) << diffuse.dump();
  const json specular = grade(student_pair("6.0", true), "specular");
  EXPECT_TRUE(specular["pass"]) << specular.dump();
}

TEST_F(GradeTest, TheHandoutsExponentIsNamedAndSoIsAnyOther) {
  const json handout = grade(student_pair("0.6", true), "specular");
  EXPECT_FALSE(handout["pass"]);
  EXPECT_EQ(handout["diagnosis"], "handout_exponent") << handout.dump();
  EXPECT_NE(handout["messages"][0].get<std::string>().find("your shader's exponent is 0.6; the course's starter uses 6.0"),
            std::string::npos) << handout.dump();
  // An exponent the catalogue does not hold is read from the source.
  const json other = grade(student_pair("20.0", true), "specular");
  EXPECT_FALSE(other["pass"]);
  EXPECT_EQ(other["diagnosis"], "changed_specularAlpha") << other.dump();
  // A render confirms the constant is the only change, and the grader's words say where it is,
  // once: not again as the repair's "`20.0` is not the number the homework uses here".
  EXPECT_EQ(other["messages"][0], "phong_frag.js line 15: your shader's exponent is 20.0; the course's starter uses 6.0 (specularAlpha).")
      << other.dump();
  for (const json& m : other["messages"]) EXPECT_EQ(m.get<std::string>().find("not the number"), std::string::npos) << other.dump();
  const json& found = handout["repairSearch"]["found"];
  EXPECT_EQ(found["kind"], "literal_refit") << handout.dump();
  EXPECT_EQ(found["line"], 15) << handout.dump();
  EXPECT_FALSE(handout["repairSearch"].contains("also")) << handout.dump();
  EXPECT_EQ(handout["messages"][0].get<std::string>().rfind("phong_frag.js line 15: your shader's exponent is 0.6", 0), 0) << handout.dump();
}

// A changed exponent is one change: a program with another as well is told both, each at its line.
TEST_F(GradeTest, AChangedExponentBesideAnotherMistakeNamesBothLines) {
  json pair = student_pair("20.0", true);
  const std::string fragment = pair["fragment"];
  const std::string view = "vec3 toEye = normalize(-vPosition);";
  ASSERT_NE(fragment.find(view), std::string::npos);
  pair["fragment"] = std::string(fragment).replace(fragment.find(view), view.size(), "vec3 toEye = normalize(vPosition);");
  const json r = grade(pair, "specular");
  EXPECT_FALSE(r["pass"]) << r["messages"].dump();
  EXPECT_EQ(r["diagnosis"], "changed_specularAlpha") << r["messages"].dump();
  const json& search = r["repairSearch"];
  ASSERT_TRUE(search.contains("found") && search.contains("also")) << r["messages"].dump();
  std::set<int> lines = {search["found"]["line"].get<int>(), search["also"]["line"].get<int>()};
  EXPECT_EQ(lines, (std::set<int>{15, 26})) << r["messages"].dump();  // specularAlpha's line and toEye's
  for (const json& repair : {search["found"], search["also"]}) {
    if (repair["line"] == 26) {
      // The student's own name for the reference's V, said in the homework's terms.
      EXPECT_EQ(repair["text"], "`toEye`, the direction to the eye, has the wrong sign") << search.dump();
    }
  }
  // Each line said once, the exponent in the grader's words about it.
  const json& m = r["messages"];
  ASSERT_GE(m.size(), 2u) << m.dump();
  const std::string said = m[0].get<std::string>() + "\n" + m[1].get<std::string>();
  EXPECT_NE(said.find("phong_frag.js line 15: your shader's exponent is 20.0; the course's starter uses 6.0"), std::string::npos) << m.dump();
  EXPECT_NE(said.find("phong_frag.js line 26: `toEye`, the direction to the eye, has the wrong sign"), std::string::npos) << m.dump();
}

TEST_F(GradeTest, AnOldCheckpointNameIsGradedAsWhatItNowMeansAndSaysSo) {
  const json r = grade(submission("normals"), "gouraud");
  EXPECT_TRUE(r["pass"]) << r.dump();
  EXPECT_EQ(r["checkpoint"], "normals");
  ASSERT_FALSE(r["warnings"].empty()) << r.dump();
  EXPECT_NE(r["warnings"].back().get<std::string>().find("'gouraud' is now 'normals'"), std::string::npos) << r.dump();
}

// The course catalogue's mistake in code is found by the repair search, with no reading of its
// own (docs/grading.md, "One explainer"): the line, and what is wrong with it.
TEST_F(GradeTest, UnnormalizedNormalsAreRecognised) {
  const json r = grade(submission("diffuse", "vec3 N = normalize(vNormal);", "vec3 N = vNormal;"), "diffuse");
  EXPECT_FALSE(r["pass"]) << r.dump();
  const json& found = r["repairSearch"]["found"];
  EXPECT_EQ(found["kind"], "normalised") << r.dump();
  EXPECT_NE(found["text"].get<std::string>().find("`N` is not normalised"), std::string::npos) << r.dump();
}

TEST_F(GradeTest, NanIsFoundEvenWhereTheCanvasShowsBlack) {
  // An unset uniform is zero, and the compiler cannot fold zero divided by it.
  json job = submission("specular", "    fragColor = color;", "    fragColor = color * (uUnset / uUnset);");
  std::string fragment = job["fragment"];
  fragment.replace(fragment.find("uniform vec4 uLightColor;"), 25, "uniform vec4 uLightColor;\nuniform float uUnset;");
  job["fragment"] = fragment;
  const json r = grade(job, "specular");
  EXPECT_FALSE(r["pass"]);
  EXPECT_EQ(r["diagnosis"], "nan") << r.dump();
  EXPECT_GT(r["frames"][0]["nanPixels"].get<int>(), 100);
  EXPECT_NE(r["messages"][0].get<std::string>().find("NaN in"), std::string::npos);
}

// Mesa folds n - n to 0 (and 0 * x to 0), so normalize(n - n) is 0 on llvmpipe where IEEE
// arithmetic, and the GPU behind the student's browser, give NaN. The grade draws the program with
// IEEE semantics (invariant outputs) and the draw's census finds it.
TEST_F(GradeTest, ANanTheOptimiserFoldsAwayIsStillFound) {
  json job = submission("specular", "    fragColor = color;", "    fragColor = vec4(normalize(vNormal.xyz - vNormal.xyz), 1.0) + 0.0 * color;");
  const json r = grade(job, "specular");
  EXPECT_FALSE(r["pass"]);
  EXPECT_EQ(r["diagnosis"], "nan") << r.dump();
  EXPECT_GT(r["frames"][0]["nanPixels"].get<int>(), 100);
}

TEST_F(GradeTest, CompileErrorsScoreZeroWithTheLine) {
  const json r = grade(submission("specular", "fragColor = color;", "fragColor = colour;"), "specular");
  EXPECT_FALSE(r["pass"]);
  EXPECT_EQ(r["score"], 0.0);
  EXPECT_EQ(r["diagnosis"], "compile_failed");
  EXPECT_NE(r["messages"][0].get<std::string>().find("compile error at phong_frag.js line"), std::string::npos) << r.dump();
}

// Shaders the browser runs that this server's driver will not (Mesa refuses a uniform of two
// precisions that only the fragment shader uses; Chromium links it) are the grader's failure,
// answered as such, never the student's 0.
TEST_F(GradeTest, ADriverThatRefusesWhatTheBrowserRunsGivesNoGrade) {
  json job = submission("specular", "void main", "uniform highp vec4 uUnusedTint;\nvoid main", true);
  std::string fragment = job["fragment"];
  fragment.replace(fragment.find("void main"), 9, "uniform mediump vec4 uUnusedTint;\nvoid main");
  fragment.replace(fragment.find("fragColor = color;"), 18, "fragColor = color + 0.0 * uUnusedTint;");
  job["fragment"] = fragment;
  job["reference"] = "specular";
  auto r = server_->client().Post("/api/grade", job.dump(), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 500) << r->body;
  const json p = json::parse(r->body);
  EXPECT_EQ(p["code"], "driver_refused") << r->body;
  EXPECT_FALSE(p.contains("score"));
  EXPECT_NE(p["detail"].get<std::string>().find("not the student's error"), std::string::npos) << r->body;
  auto metrics = server_->client().Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_EQ(metrics->body.find("shadelab_driver_refusals_total 0"), std::string::npos);
}

TEST_F(GradeTest, GradescopeOutputHasEveryRequiredField) {
  json job = submission("diffuse");
  job["format"] = "gradescope";
  job["maxScore"] = 2;
  const json r = grade(job, "specular");
  for (const char* field : {"score", "execution_time", "tests"}) EXPECT_TRUE(r.contains(field)) << field;
  ASSERT_EQ(r["tests"].size(), 1u);
  for (const char* field : {"name", "score", "max_score", "status", "output", "visibility"})
    EXPECT_TRUE(r["tests"][0].contains(field)) << field;
  EXPECT_EQ(r["tests"][0]["max_score"], 2.0);
  EXPECT_EQ(r["tests"][0]["status"], "failed");
  EXPECT_GT(r["execution_time"].get<double>(), 0.0);
}

TEST_F(GradeTest, MultipartUploadAndACustomReferencePairWork) {
  const auto diffuse = *testkit::course().preset("diffuse");
  const auto smooth = *testkit::course().preset("smooth");
  httplib::MultipartFormDataItems items = {
      {"vertex", diffuse.vertex.text, "phong_vert.js", ""},
      {"fragment", diffuse.fragment.text, "phong_frag.js", ""},
      {"referenceVertex", smooth.vertex.text, "ref_vert.js", ""},
      {"referenceFragment", smooth.fragment.text, "ref_frag.js", ""},
      {"width", "96", "", ""},
      {"height", "72", "", ""}};
  auto r = server_->client().Post("/api/grade", items);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const json j = json::parse(r->body);
  EXPECT_EQ(j["checkpoint"], "custom");
  EXPECT_FALSE(j["pass"]);  // diffuse shading is not the normal-colour reference
  testkit::expect_conforms(*r, "/api/grade", "post");

  items[0] = {"vertex", smooth.vertex.text, "starter_vert.js", ""};
  items[1] = {"fragment", smooth.fragment.text, "starter_frag.js", ""};
  r = server_->client().Post("/api/grade", items);
  ASSERT_TRUE(r);
  EXPECT_TRUE(json::parse(r->body)["pass"]) << r->body;
}

TEST_F(GradeTest, BadGradeRequestsAreProblems) {
  json job = submission("specular");
  job["reference"] = "phong";
  auto r = server_->client().Post("/api/grade", job.dump(), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
  job["reference"] = "specular";
  job["fragment"] = "void main() {}";  // GLSL ES 1.00 beside an ES 3.00 vertex shader: graded 0, even with a mistyped maxScore
  job["maxScore"] = "lots";
  r = server_->client().Post("/api/grade", job.dump(), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(json::parse(r->body)["diagnosis"], "link_failed");
  job = submission("specular");
  job["reference"] = "specular";
  job["threshold"] = 3;
  r = server_->client().Post("/api/grade", job.dump(), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  testkit::expect_conforms(*r, "/api/grade", "post");
}

// The frames a student saved, over HTTP in both forms: multipart (one `frames` part per file, as
// curl -F and the page send them) with the code beside them, and JSON (`savedFrames`, base64).
TEST_F(GradeTest, SavedFramesAreGradedOverHttpInBothForms) {
  const auto frames = testkit::saved_frames("specular", "specular", {0, 0.2, 0.1, 0.3, 0.05, 0.25, 0.15, 0.2, 0.1});
  ASSERT_EQ(frames.size(), 9u);
  const auto code = *testkit::course().preset("specular");
  httplib::MultipartFormDataItems items = {{"reference", "specular", "", ""},
                                           {"vertex", code.vertex.text, "phong_vert.js", ""},
                                           {"fragment", code.fragment.text, "phong_frag.js", ""},
                                           {"frames", "not a frame", "notes.txt", ""}};
  for (auto it = frames.rbegin(); it != frames.rend(); ++it) items.push_back({"frames", it->bytes, it->name, "image/png"});  // any order
  auto r = server_->client().Post("/api/grade", items);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  testkit::expect_conforms(*r, "/api/grade", "post");
  json j = json::parse(r->body);
  EXPECT_EQ(j["deliverable"], "specular");
  EXPECT_TRUE(j["frames"]["pass"]) << j["frames"]["messages"];
  EXPECT_TRUE(j["code"]["pass"]) << j["code"]["messages"];
  EXPECT_NEAR(j["frames"]["frames"][3]["lagDegrees"].get<double>(), 0.3, 0.05);
  ASSERT_EQ(j["frames"]["warnings"].size(), 1u);
  EXPECT_NE(j["frames"]["warnings"][0].get<std::string>().find("notes.txt is not one of the specular deliverable's frames"), std::string::npos);

  // JSON, one frame short: the frames' grade names it (a student's mistake, not a bad request).
  json body = {{"reference", "specular"}, {"savedFrames", json::array()}};
  for (size_t k = 0; k + 1 < frames.size(); ++k) body["savedFrames"].push_back({{"name", frames[k].name}, {"png", base64_encode(frames[k].bytes)}});
  r = server_->client().Post("/api/grade", body.dump(), "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  testkit::expect_conforms(*r, "/api/grade", "post");
  j = json::parse(r->body);
  EXPECT_FALSE(j["frames"]["pass"]);
  EXPECT_EQ(j["frames"]["diagnosis"], "frames_invalid");
  EXPECT_NE(j["frames"]["messages"][0].get<std::string>().find("hw2_specular_8.png is missing"), std::string::npos) << j["frames"]["messages"];
  EXPECT_FALSE(j.contains("code"));

  // What is not a student's mistake is a problem: no deliverable named, frames not base64, Gradescope's format.
  for (const json& wrong : {json{{"savedFrames", body["savedFrames"]}}, json{{"reference", "specular"}, {"savedFrames", {{{"name", "a.png"}, {"png", "%%"}}}}},
                            json{{"reference", "specular"}, {"format", "gradescope"}, {"savedFrames", body["savedFrames"]}}}) {
    r = server_->client().Post("/api/grade", wrong.dump(), "application/json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400) << r->body;
    testkit::expect_conforms(*r, "/api/grade", "post");
  }
}

}  // namespace

// /metrics says what each worker holds: its resident set, and after a grade the reference renders
// it keeps for the next submission (bounded) and the programs it keeps warm.
TEST_F(GradeTest, MetricsReportWhatEachWorkerKeeps) {
  grade(submission("specular"), "specular");
  auto r = server_->client().Get("/metrics");
  ASSERT_TRUE(r);
  const auto values = [&](const std::string& name) {
    std::vector<double> out;
    for (size_t at = r->body.find(name + "{worker=\""); at != std::string::npos; at = r->body.find(name + "{worker=\"", at + 1))
      out.push_back(std::stod(r->body.substr(r->body.find("} ", at) + 2)));
    return out;
  };
  const auto resident = values("shadelab_worker_resident_bytes");
  const auto references = values("shadelab_worker_reference_cache_bytes");
  const auto programs = values("shadelab_worker_cached_programs");
  ASSERT_EQ(resident.size(), 2u) << r->body;  // one per worker of the test server
  for (double v : resident) EXPECT_GT(v, 10e6);
  ASSERT_EQ(references.size(), 2u);
  const double held = std::max(references[0], references[1]);
  EXPECT_GT(held, 160.0 * 120 * 4 * 9);  // at least the reference's 9 frames at 160 x 120
  EXPECT_LE(held, double(grade::ReferenceCache::kDefaultBytes));
  ASSERT_EQ(programs.size(), 2u);
  EXPECT_GE(std::max(programs[0], programs[1]), 1.0);
  EXPECT_LE(std::max(programs[0], programs[1]), 32.0);
  const auto mesh_bytes = values("shadelab_worker_cached_mesh_bytes");
  ASSERT_EQ(mesh_bytes.size(), 2u);
  const double bunny = double(scene::bytes_of(testkit::builtin("bunny")));
  EXPECT_GT(std::max(mesh_bytes[0], mesh_bytes[1]), bunny) << "the parsed bunny and its buffers";
  EXPECT_LE(std::max(mesh_bytes[0], mesh_bytes[1]), double((384u + 256u) << 20) + 2 * bunny);
  // Which kind of job needed it: a grade's peak is at least what a worker holds after it.
  const std::string peak = "shadelab_job_peak_resident_bytes{kind=\"grade\"} ";
  const size_t at = r->body.find(peak);
  ASSERT_NE(at, std::string::npos) << r->body;
  const double grade_peak = std::stod(r->body.substr(at + peak.size()));
  EXPECT_GT(grade_peak, 10e6);
  EXPECT_LE(grade_peak, double(testkit::test_config().pool.memory_limit_bytes));
}

// The reference cache keeps what fits its byte budget, the least recently used out first, so a
// worker that has graded many checkpoints holds at most the budget.
// The grader's own diagnoses: each id names one diagnosis and reads back as it, each says what it
// means, and none is an error code's or a flag's word for something else.
TEST(DiagnosisTest, EachIdIsOneDiagnosisWithItsMeaning) {
  std::set<std::string> ids;
  for (int k = 0; k <= static_cast<int>(grade::Diagnosis::made_by_shadelab); ++k) {
    const auto d = static_cast<grade::Diagnosis>(k);
    const std::string id = grade::to_string(d);
    EXPECT_TRUE(ids.insert(id).second) << id << " twice";
    EXPECT_EQ(grade::diagnosis_named(id), d) << id;
    EXPECT_FALSE(grade::meaning(d).empty()) << id;
  }
  EXPECT_FALSE(grade::diagnosis_named("missing_specular")) << "the catalogue's ids are the course's";
  EXPECT_EQ(grade::changed_constant_diagnosis("specularAlpha"), "changed_specularAlpha");
}

TEST(ReferenceCacheTest, EvictsTheLeastRecentlyUsedWithinItsBudget) {
  const auto frames_of_bytes = [](std::size_t n) {
    auto image = std::make_shared<image::Image>();
    image->bytes.resize(n);
    return grade::SharedFrames{image};
  };
  grade::ReferenceCache cache(300);
  cache.insert("a", frames_of_bytes(100));
  cache.insert("b", frames_of_bytes(100));
  cache.insert("c", frames_of_bytes(100));
  EXPECT_EQ(cache.bytes(), 300u);
  ASSERT_NE(cache.find("a"), nullptr);  // "a" is now the newest; "b" the oldest
  cache.insert("d", frames_of_bytes(100));
  EXPECT_EQ(cache.find("b"), nullptr);
  EXPECT_NE(cache.find("a"), nullptr);
  EXPECT_NE(cache.find("c"), nullptr);
  EXPECT_NE(cache.find("d"), nullptr);
  EXPECT_EQ(cache.bytes(), 300u);
  cache.insert("huge", frames_of_bytes(301));  // larger than the whole budget: not kept, nothing evicted
  EXPECT_EQ(cache.find("huge"), nullptr);
  EXPECT_EQ(cache.bytes(), 300u);
  EXPECT_NE(cache.find("a"), nullptr);
}

// The caches a worker keeps between jobs: a count and a byte budget, the least recently used out
// first; the entry just inserted stays even when it alone is over budget (its job is using it).
TEST(LruCacheTest, EvictsTheLeastRecentlyUsedWithinItsCountAndBytes) {
  LruCache<int> cache(3, 100);
  cache.insert("a", 1, 10);
  cache.insert("b", 2, 10);
  cache.insert("c", 3, 10);
  ASSERT_NE(cache.find("a"), nullptr);  // "a" is now the newest; "b" the oldest
  EXPECT_EQ(cache.insert("d", 4, 10), 4);
  EXPECT_EQ(cache.find("b"), nullptr) << "a fourth entry evicts the least recently used";
  EXPECT_EQ(cache.size(), 3u);
  EXPECT_EQ(cache.bytes(), 30u);
  cache.insert("e", 5, 85);  // "c" goes for the count; then 20 + 85 > 100, so "a" goes for the bytes
  EXPECT_EQ(cache.find("c"), nullptr);
  EXPECT_EQ(cache.find("a"), nullptr);
  EXPECT_EQ(cache.bytes(), 95u);
  EXPECT_EQ(*cache.find("d"), 4);
  EXPECT_EQ(cache.insert("huge", 6, 500), 6) << "kept for the job that inserted it";
  EXPECT_EQ(cache.size(), 1u);
  EXPECT_EQ(cache.bytes(), 500u);
  cache.insert("f", 7, 10);
  EXPECT_EQ(cache.find("huge"), nullptr) << "and out at the next insert";
  EXPECT_EQ(cache.bytes(), 10u);
}

// A wrong shader the catalogue does not hold (another exponent) is graded once: its diagnosis (the
// catalogue's renders, the comparisons, the repair search) is the grader's work, outside the
// student's deadline, so it is never stopped and retried, and the catalogue comes from the
// worker's memory. What it costs against a passing grade is a benchmark's figure
// (bench/mutation_bench.py, docs/grading.md "Repairs"), not this test's: a timed bound failed
// under load (2.6x with the machine busy, 2.0x quiet).
TEST(GraderTimeTest, AnUncataloguedMistakeIsGradedOnceAndNeverRetried) {
  auto config = testkit::test_config();
  config.pool.workers = 1;
  testkit::RunningService server(std::move(config));
  ASSERT_TRUE(server.ok()) << server.failure;
  const auto grade = [&](json job) {
    job["reference"] = "specular";
    auto r = server.client().Post("/api/grade", job.dump(), "application/json");
    EXPECT_TRUE(r && r->status == 200) << (r ? r->body : "no response");
    return r ? json::parse(r->body) : json::object();
  };
  // A fresh shader each time (Mesa caches programs by their IR): a never-taken branch on a new
  // constant; a return, not a discard, which would have the grade draw a light at a time.
  const auto fresh = [](json job, int serial) {
    std::string f = job["fragment"];
    const std::string entry = "void main(void) {";
    f.insert(f.find(entry) + entry.size(), "\n    if (gl_FragCoord.x < -" + std::to_string(serial) + ".0) { fragColor = vec4(1.0); return; }");
    job["fragment"] = f;
    return job;
  };
  grade(student_pair("0.6", true));  // the catalogue into the worker's memory (a catalogued mistake)
  for (int i = 0; i < 3; ++i) {
    const json pass = grade(fresh(student_pair("6.0", true), 2 * i + 1));
    EXPECT_TRUE(pass["pass"]) << pass.dump();
    const json wrong = grade(fresh(student_pair("20.0", true), 2 * i + 2));
    EXPECT_FALSE(wrong["pass"]);
    EXPECT_EQ(wrong["attempts"], 1) << wrong.dump();
    for (const auto& m : wrong["messages"]) EXPECT_EQ(m.get<std::string>().find("stopped"), std::string::npos) << m;
    EXPECT_EQ(wrong["diagnosis"], "changed_specularAlpha");
    EXPECT_EQ(wrong["graderWork"]["rendered"], 0) << "the catalogue came from memory: " << wrong["graderWork"];
    EXPECT_EQ(wrong["repairSearch"]["found"]["kind"], "literal_refit") << wrong["repairSearch"];
  }
}

// The starter's constants read from a student's source: the first assignment of a literal, not a
// comment, not another name, not a comparison; linear on a stranger's bytes.
TEST(StarterConstantsTest, TheFirstAssignedLiteralIsReadAndNothingElse) {
  const std::vector<grade::StarterConstant> exponent = {{"specularAlpha", "exponent", 6.0}};
  const auto found = [&](const std::string& source) {
    const auto f = grade::changed_starter_constants(exponent, source);
    return f.empty() ? std::string() : f[0].message;
  };
  EXPECT_EQ(found("float specularAlpha = 20.0;"), "your shader's exponent is 20.0; the course's starter uses 6.0 (specularAlpha)");
  EXPECT_EQ(found("  float specularAlpha=0.6 ;\n"), "your shader's exponent is 0.6; the course's starter uses 6.0 (specularAlpha)");
  EXPECT_EQ(found("float specularAlpha = 6.0;"), "") << "the starter's own value";
  EXPECT_EQ(found("float specularAlpha = 6.;"), "") << "the same number, written otherwise";
  EXPECT_EQ(found("// float specularAlpha = 0.6;\nfloat specularAlpha = 6.0;"), "") << "a comment is not the code";
  EXPECT_EQ(found("/* specularAlpha = 1.0; */ float specularAlpha = 6.0;"), "");
  EXPECT_EQ(found("float mySpecularAlpha2 = 1.0; float specularAlphaX = 2.0;"), "") << "other names";
  EXPECT_EQ(found("if (specularAlpha == 1.0) {}"), "") << "a comparison";
  EXPECT_EQ(found("float specularAlpha = uShininess;"), "") << "not a literal";
  EXPECT_EQ(found("float specularAlpha = 1e1;"), "your shader's exponent is 1e1; the course's starter uses 6.0 (specularAlpha)");
  // A megabyte of spaces between the name and its value, and a megabyte of the name: no recursion.
  EXPECT_EQ(found("float specularAlpha" + std::string(1 << 20, ' ') + "= 2.0;"),
            "your shader's exponent is 2.0; the course's starter uses 6.0 (specularAlpha)");
  std::string names;
  for (int i = 0; i < 60000; ++i) names += "specularAlpha ";
  EXPECT_EQ(found(names), "");
}

// The heat map is drawn only where somebody looks at it: always for the page (and --heatmap), for a
// failing grade only in Gradescope (a passing test shows none), never in a class batch.
TEST(GradeHeatMapTest, IsDrawnOnlyWhereItIsShown) {
  const course::Course& c = testkit::course();
  grade::GradeSpec spec = c.grade_spec(*c.checkpoint("specular")->checkpoint, {});
  const auto* right = c.preset("specular");
  const auto* wrong = c.preset("diffuse");
  grade::GradeRenders renders(testkit::shared_renderer());
  const auto heatmap = [&](grade::HeatMap policy, const course::Preset& p) {
    spec.heatmap = policy;
    render::RenderRequest r = c.render_request(p.vertex, p.fragment);
    r.frames = 1;
    r.width = r.height = 64;
    auto out = grade::judge_code(renders, spec, r, [] { return Expected<const scene::Mesh*>(&testkit::builtin(testkit::course().default_mesh)); },
                             "bunny", [](JobPhase) -> Status { return Ok{}; });
    EXPECT_TRUE(out) << out.error().format();
    EXPECT_EQ(out->report.pass, &p == right);
    return out ? out->heatmap_png : std::string();
  };
  EXPECT_FALSE(heatmap(grade::HeatMap::always, *right).empty());
  EXPECT_FALSE(heatmap(grade::HeatMap::always, *wrong).empty());
  EXPECT_TRUE(heatmap(grade::HeatMap::when_failing, *right).empty());
  EXPECT_FALSE(heatmap(grade::HeatMap::when_failing, *wrong).empty());
  EXPECT_TRUE(heatmap(grade::HeatMap::never, *right).empty());
  EXPECT_TRUE(heatmap(grade::HeatMap::never, *wrong).empty());
}
