// Course profiles (server/course/): the built-in one round-trips; a bad file is refused with the
// field and the reason; `shadelab course import` reads a homework folder written for this test
// (never the course's own page code); and a profile with another canvas and light renders and
// grades with them end to end, on the command line and through the server.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/base64.h"
#include "course/course_import.h"
#include "course/course_reader.h"
#include "course/script_facts.h"
#include "course/unseen_roles.h"
#include "model/lighting.h"
#include "support/files.h"
#include "support/http_fixture.h"
#include "support/openapi_check.h"
#include "support/run_command.h"
#include "support/test_support.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace shadelab;

namespace {

const fs::path kSource = SHADELAB_SOURCE_DIR;

using CliRun = testkit::CommandRun;
CliRun run_cli(const std::string& args) { return testkit::run_shadelab(args); }

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

std::vector<std::uint8_t> bytes_of(const std::string& s) { return {s.begin(), s.end()}; }

json builtin_json() { return json::parse(testkit::read_text(kSource / "courses/cs148-summer2022.json")); }

// The error a profile gets when read as if it sat in courses/ (its files the repository's).
std::string error_of(const json& profile) {
  auto read = course::read_course(profile.dump(), course::embedded_source("courses"), "test.json");
  return read ? std::string("(read)") : read.error().message;
}

}  // namespace

TEST(CourseProfileTest, TheBuiltInProfileRoundTripsFieldForField) {
  const course::Course& c = course::builtin_course();
  const json written = course::to_json(c);
  auto again = course::read_course(written.dump(), course::embedded_source("courses"), "round trip");
  ASSERT_TRUE(again) << again.error().message;
  EXPECT_EQ(course::to_json(*again), written);
  EXPECT_EQ(written, builtin_json()) << "the file holds exactly what the reader keeps";
  json shown = builtin_json();
  shown["repairShown"] = "what";
  auto what = course::read_course(shown.dump(), course::embedded_source("courses"), "repairShown");
  ASSERT_TRUE(what) << what.error().message;
  EXPECT_EQ(what->repair_shown, repair::RepairShown::what);
  EXPECT_EQ(course::to_json(*what), shown) << "a course's choice of what its students read of a repair is kept";
  // Portable: every file named where it was read, so the JSON loads from any folder.
  const json portable = course::to_json(c, true);
  EXPECT_EQ(portable["meshes"][0]["file"], "builtin:assets/bunny.obj");
  auto elsewhere = course::read_course(portable.dump(), course::folder_source("/nonexistent"), "portable");
  ASSERT_TRUE(elsewhere) << elsewhere.error().message;
  EXPECT_EQ(course::to_json(*elsewhere), portable);
}

TEST(CourseProfileTest, ABadProfileIsRefusedWithTheFieldAndTheReason) {
  const auto with = [](const std::function<void(json&)>& change) {
    json j = builtin_json();
    change(j);
    return error_of(j);
  };
  EXPECT_EQ(error_of(builtin_json()), "(read)");
  EXPECT_EQ(with([](json& j) { j["canvas"]["width"] = "wide"; }), "test.json: canvas.width: expected an integer in [1, 16384]");
  EXPECT_EQ(with([](json& j) { j["canvas"].erase("height"); }), "test.json: canvas.height: missing (required)");
  EXPECT_EQ(with([](json& j) { j["msaaa"] = 4; }), "test.json: msaaa: unknown field");
  EXPECT_EQ(with([](json& j) { j["repairShown"] = "everything"; }), "test.json: repairShown: expected one of repairedLine, what, where");
  EXPECT_EQ(with([](json& j) { j["format"] = "shadelab-course-2"; }),
            "test.json: format: expected \"shadelab-course-1\" (this ShadeLab reads that version of the format)");
  EXPECT_EQ(with([](json& j) { j["checkpoints"][2]["prefix"] = "spec ular"; }),
            "test.json: checkpoints[2].prefix: expected letters, digits, '_' or '-' (at most 64)");
  EXPECT_EQ(with([](json& j) { j["checkpoints"][2]["mistakes"][3]["edits"][0]["find"] = "if (NdotL >= 0.0) {"; }),
            "test.json: checkpoints[2].mistakes[3].edits[0].find: 'if (NdotL >= 0.0) {' is not in specular_frag.js (the reference 'specular')");
  EXPECT_EQ(with([](json& j) { j["checkpoints"][0]["reference"] = "gouraud"; }), "test.json: checkpoints[0].reference: 'gouraud' is not one of presets");
  EXPECT_EQ(with([](json& j) { j["meshes"][1]["file"] = "../assets/dragon.obj"; }),
            "test.json: meshes[1].file: no file 'assets/dragon.obj' is compiled into this binary");
  EXPECT_EQ(with([](json& j) { j["uniforms"][3]["value"] = {16, 8}; }), "test.json: uniforms[3].value: a vec3 takes 3 numbers");
  EXPECT_EQ(with([](json& j) { j["specularExponent"]["value"] = 0.6; }),
            "test.json: presets[4].fragment: specular_frag.js sets specularAlpha otherwise than specularExponent.value (your shader's "
            "exponent is 6.0; the course's starter uses 0.6 (specularAlpha))");
  EXPECT_EQ(with([](json& j) { j["checkpoints"][1]["mistakes"][0] = {{"id", "nothing"}, {"message", "x"}, {"preset", "diffuse"}}; }),
            "test.json: checkpoints[1].mistakes[0]: the mistake's shaders are the reference's own: it would match every correct submission");
  EXPECT_EQ(with([](json& j) { j["aliases"][0]["checkpoint"] = "phong"; }), "test.json: aliases[0].checkpoint: 'phong' is not one of checkpoints");
  // A mistake's reading names the formula's own variants and values, on a checkpoint with a formula.
  EXPECT_EQ(with([](json& j) { j["checkpoints"][2]["mistakes"][2]["reading"] = {{"variant", "blinn"}}; }),
            "test.json: checkpoints[2].mistakes[2].reading.variant: 'blinn' is not one of the formula's variants");
  EXPECT_EQ(with([](json& j) { j["checkpoints"][2]["mistakes"][2]["reading"]["values"] = {{"shininess", {12}}}; }),
            "test.json: checkpoints[2].mistakes[2].reading.values.shininess: expected ambient, diffuse, specular, exponent or lightPosition");
  EXPECT_TRUE(with([](json& j) { j["checkpoints"][2]["mistakes"][5]["reading"]["values"]["exponent"] = {0.6, 6}; })
                  .starts_with("test.json: checkpoints[2].mistakes[5].reading.values.exponent: "));
  EXPECT_EQ(with([](json& j) {
              j["checkpoints"][0].erase("formula");
              j["checkpoints"][0]["mistakes"][0]["reading"] = {{"variant", "flat_colour"}};
            }),
            "test.json: checkpoints[0].mistakes[0].reading: a reading is the formula's: the checkpoint has no formula");
  // The normals' formula: its own variants, no values, the colour varying its reference writes.
  EXPECT_EQ(with([](json& j) { j["checkpoints"][0]["mistakes"][0]["reading"] = {{"variant", "flat_normal"}}; }),
            "test.json: checkpoints[0].mistakes[0].reading.variant: 'flat_normal' is not a variant of a normalColour formula");
  EXPECT_EQ(with([](json& j) { j["checkpoints"][1]["mistakes"][0]["reading"] = {{"variant", "missing_abs"}}; }),
            "test.json: checkpoints[1].mistakes[0].reading.variant: 'missing_abs' is not a variant of a lambert formula");
  EXPECT_EQ(with([](json& j) { j["checkpoints"][0]["mistakes"][0]["reading"]["values"] = {{"ambient", {0.4, 0.2, 0.2}}}; }),
            "test.json: checkpoints[0].mistakes[0].reading.values: the normal's colour has no values to change");
  EXPECT_EQ(with([](json& j) { j["checkpoints"][0]["formula"]["colour"] = "vNormalColour"; }),
            "test.json: checkpoints[0].formula.colour: the reference's vertex shader declares no `out vec3 vNormalColour;` or `out vec4 vNormalColour;`");
  EXPECT_EQ(with([](json& j) { j["checkpoints"][0]["formula"].erase("geometry"); }),
            "test.json: checkpoints[0].formula.position: the reference's vertex shader declares no `out vec3 vPosition;`");
  EXPECT_EQ(with([](json& j) { j["checkpoints"][0]["formula"]["geometry"] = "shiny"; }),
            "test.json: checkpoints[0].formula.geometry: 'shiny' is not one of presets");
  // The formula's vectors: its own names, each a vec3 local of the reference's fragment shader.
  EXPECT_EQ(with([](json& j) { j["checkpoints"][2]["formula"]["vectors"]["eye"] = "V"; }),
            "test.json: checkpoints[2].formula.vectors.eye: expected normal, light, view or reflected");
  EXPECT_EQ(with([](json& j) { j["checkpoints"][2]["formula"]["vectors"]["view"] = "toEye"; }),
            "test.json: checkpoints[2].formula.vectors.view: the reference's fragment shader declares no `vec3 toEye`");
  EXPECT_EQ(with([](json& j) { j["checkpoints"][2]["formula"]["vectors"]["view"] = "V)"; }),
            "test.json: checkpoints[2].formula.vectors.view: expected a local's name");
  EXPECT_EQ(error_of(json::array()), "test.json: a course profile must be a JSON object");
  // Through the command line: the same words, and the failure's code.
  const fs::path bad = fs::temp_directory_path() / ("shadelab_course_bad_" + std::to_string(::getpid()) + ".json");
  json j = builtin_json();
  j["frames"]["fileName"] = "frames_{k}";
  for (auto& m : j["meshes"]) m["file"] = "builtin:" + m["file"].get<std::string>().substr(3);
  for (auto& p : j["presets"])
    for (const char* stage : {"vertex", "fragment"}) p[stage] = "builtin:" + p[stage].get<std::string>().substr(3);
  write(bad, j.dump());
  const auto run = run_cli("course check " + bad.string());
  fs::remove(bad);
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("frames.fileName: expected a name holding {prefix} and {k}"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("[course_invalid]"), std::string::npos) << run.output;
}

// Debian's JSON Schema validator on `profile` against docs/course-profile.schema.json: "" when it
// validates, else its first complaint.
std::string schema_error(const json& profile) {
  const fs::path file = fs::temp_directory_path() / ("shadelab_schema_" + std::to_string(::getpid()) + ".json");
  write(file, profile.dump());
  const std::string script =
      "import json, sys, jsonschema\n"
      "schema = json.load(open(sys.argv[1]))\n"
      "errors = sorted(jsonschema.Draft202012Validator(schema).iter_errors(json.load(open(sys.argv[2]))), key=lambda e: list(e.path))\n"
      "print('/'.join(str(p) for p in errors[0].path) + ': ' + errors[0].message if errors else '', end='')\n";
  write(file.string() + ".py", script);
  const std::string out = testkit::run_command("/usr/bin/python3 " + file.string() + ".py " +
                                              (kSource / "docs/course-profile.schema.json").string() + " " + file.string())
                              .output;
  fs::remove(file);
  fs::remove(file.string() + ".py");
  return out;
}

// The schema and the reader agree: each accepts the built-in profile, and each refuses what the
// other refuses among the mistakes a schema can see. (What only the reader can check, that a file
// exists, that a mistake's edit is in its reference, that a name is not used twice, is the
// reader's alone: ABadProfileIsRefusedWithTheFieldAndTheReason.)
// A course's tolerance reaches every grade of it (Course::grade_options), written back only where
// it is not the default; out of range or unknown, it is refused by field.
TEST(CourseProfileTest, ACoursesToleranceIsItsGradesThresholds) {
  json j = builtin_json();
  j["tolerance"] = {{"threshold", 0.05}, {"sameOutline", 0.8}};
  auto read = course::read_course(j.dump(), course::embedded_source("courses"), "test.json");
  ASSERT_TRUE(read) << read.error().message;
  const auto& specular = *read->checkpoint("specular")->checkpoint;
  const grade::GradeOptions options = read->grade_options(specular);
  EXPECT_EQ(options.compare.threshold, 0.05);
  EXPECT_EQ(options.same_outline, 0.8);
  EXPECT_EQ(options.max_failing_fraction, grade::GradeOptions{}.max_failing_fraction);
  EXPECT_EQ(options.max_score, specular.points);
  EXPECT_EQ(read->grade_spec(specular, options).options.compare.threshold, 0.05);
  EXPECT_EQ(course::to_json(*read, false)["tolerance"], j["tolerance"]);
  EXPECT_FALSE(course::to_json(course::builtin_course(), false).contains("tolerance")) << "the defaults are not written";
  j["tolerance"] = {{"threshold", 2}};
  EXPECT_EQ(error_of(j), "test.json: tolerance.threshold: expected a number in [0, 1]");
  EXPECT_TRUE(schema_error(j).starts_with("tolerance/threshold:")) << schema_error(j);
  j["tolerance"] = {{"treshold", 0.1}};
  EXPECT_EQ(error_of(j), "test.json: tolerance.treshold: unknown field");
}

TEST(CourseProfileTest, TheSchemaAndTheReaderAgree) {
  EXPECT_EQ(schema_error(builtin_json()), "");
  EXPECT_EQ(error_of(builtin_json()), "(read)");
  const std::vector<std::pair<std::string, std::function<void(json&)>>> bad = {
      {"canvas/width", [](json& j) { j["canvas"]["width"] = "wide"; }},
      {"canvas", [](json& j) { j["canvas"].erase("height"); }},
      {"", [](json& j) { j["msaaa"] = 4; }},
      {"format", [](json& j) { j["format"] = "shadelab-course-2"; }},
      {"checkpoints/2/prefix", [](json& j) { j["checkpoints"][2]["prefix"] = "spec ular"; }},
      {"meshes/0/file", [](json& j) { j["meshes"][0]["file"] = "../assets/bunny.ply"; }},
      {"frames/fileName", [](json& j) { j["frames"]["fileName"] = "frame_{k}"; }},
      {"uniforms/0/role", [](json& j) { j["uniforms"][0]["role"] = "rim"; }},
      {"checkpoints/1/mistakes/0", [](json& j) { j["checkpoints"][1]["mistakes"][0]["preset"] = "specular"; }},
      {"notebook/images/0/file", [](json& j) { j["notebook"]["images"][0]["file"] = "/etc/passwd.png"; }},
      {"camera/fovYDegrees", [](json& j) { j["camera"]["fovYDegrees"] = 180; }},
      {"checkpoints/2/mistakes/2/reading/variant", [](json& j) { j["checkpoints"][2]["mistakes"][2]["reading"] = {{"variant", "blinn"}}; }},
      {"checkpoints/2/formula/vectors", [](json& j) { j["checkpoints"][2]["formula"]["vectors"]["eye"] = "V"; }},
  };
  for (const auto& [where, change] : bad) {
    json j = builtin_json();
    change(j);
    const std::string by_schema = schema_error(j), by_reader = error_of(j);
    EXPECT_TRUE(by_schema.starts_with(where + ":")) << where << ": the schema says '" << by_schema << "'";
    EXPECT_NE(by_reader, "(read)") << where << ": the reader took it";
  }
}

// A mistake's reading names the formula's variants as the model's table does (model/lighting.cpp).
TEST(CourseProfileTest, TheSchemaNamesEveryVariantOfTheFormula) {
  std::ifstream in(kSource / "docs/course-profile.schema.json");
  const json schema = json::parse(in);
  std::vector<std::string> named, variants;
  for (const auto& v : schema["$defs"]["mistake"]["properties"]["reading"]["properties"]["variant"]["enum"]) named.push_back(v);
  for (const auto& v : model::variants()) variants.emplace_back(v.id);
  EXPECT_EQ(named, variants);
}

// The page script's facts as a course writes them: numbers by name, small arithmetic, a helper's
// arguments in its own order. What it cannot read it does not state.
// `course check`'s warning: a colour no light of a checkpoint shows (course/unseen_roles.h).
TEST(CourseProfileTest, AColourNoLightShowsIsNamed) {
  EXPECT_TRUE(course::unseen_roles(testkit::course()).empty()) << "the built-in course's orange probes show uLightColor";
  course::Course c = testkit::course();
  for (auto& k : c.checkpoints) std::erase_if(k.probes, [](const grade::Probe& p) { return p.light_color.has_value(); });
  auto unseen = course::unseen_roles(c);
  ASSERT_EQ(unseen.size(), 2u);
  EXPECT_EQ(unseen[0].checkpoint, "diffuse");
  EXPECT_EQ(unseen[1].checkpoint, "specular");
  EXPECT_EQ(unseen[1].role, course::UniformRole::light_color);
  EXPECT_EQ(unseen[1].why, "uLightColor is (1, 1, 1) under the page's light and every probe of specular: a shader that leaves it out draws the same, "
                           "and passes; give a probe a lightColor");
  for (auto& u : c.uniforms)
    if (u.role == course::UniformRole::specular) u.value = {1, 1, 1, 1};
  unseen = course::unseen_roles(c);
  EXPECT_TRUE(std::any_of(unseen.begin(), unseen.end(), [](const course::UnseenRole& r) {
    return r.checkpoint == "specular" && r.role == course::UniformRole::specular;
  })) << "a white specular colour: no light shows a term that leaves it out";
}

TEST(ScriptFactsTest, NumbersByNameAndSmallArithmetic) {
  const course::ScriptFacts js(R"(const fieldOfView = 45.0; // degrees
const zNear = 0.1, unused = 3  // no semicolon: the line ends the statement
let zFar = 100.0;
zFar = 5.0;  /* a later assignment: the declaration stands */
const half = fieldOfView / 2;
const spin = -(2 + 3) * 4;
const away = [-0.0, -2.0, -7.5];
const colour = new Float32Array([0.2, zNear, 1.0]);
const loop = loop + 1;)");
  EXPECT_EQ(js.number("fieldOfView"), 45.0);
  EXPECT_EQ(js.number("zFar"), 100.0);
  EXPECT_EQ(js.number("half * 2"), 45.0);
  EXPECT_EQ(js.number("spin"), -20.0);
  EXPECT_NEAR(*js.number("45 * Math.PI / 180"), 0.785398, 1e-6);
  EXPECT_NEAR(*js.number("glMatrix.toRadian(fieldOfView)"), 0.785398, 1e-6);
  EXPECT_EQ(js.numbers("away"), std::vector<double>({-0.0, -2.0, -7.5}));
  EXPECT_EQ(js.numbers("colour"), std::vector<double>({0.2, 0.1, 1.0}));
  EXPECT_EQ(js.number("zNear"), 0.1) << "one declaration of two names";
  EXPECT_EQ(js.number("unused"), 3.0);
  EXPECT_FALSE(js.number("canvas.width / canvas.height")) << "the page's size is not the script's to state";
  EXPECT_FALSE(js.number("loop")) << "a name bound to itself";
  EXPECT_FALSE(js.number("Math.sin(1)"));
  EXPECT_FALSE(js.number("1 / 0"));
}

TEST(ScriptFactsTest, ACallsArgumentsAreItsOwnNotItsDefinitions) {
  const course::ScriptFacts js(R"js(function mat4Perspective(out, fovy, aspect, near, far) { return out; }
const url = "http://example.com/mat4Perspective(1, 2)";
mat4Perspective(ProjectionMatrix, fieldOfView, gl.canvas.width / gl.canvas.height, zNear, zFar);
notmat4Perspective(1, 2, 3);)js");
  const auto calls = js.calls(std::regex("mat4Perspective"));
  ASSERT_EQ(calls.size(), 1u) << "the definition, the string's text and a longer name are not calls";
  EXPECT_EQ(calls[0], std::vector<std::string>({"ProjectionMatrix", "fieldOfView", "gl.canvas.width / gl.canvas.height", "zNear", "zFar"}));
}

TEST(ScriptFactsTest, ThePagesCameraAndSpinInEachFormACourseWrites) {
  const course::ScriptFacts named(R"(const fieldOfView = 45.0; const zNear = 0.1; const zFar = 100.0;
mat4Perspective(ProjectionMatrix, fieldOfView, aspect, zNear, zFar);
mat4Translate(MeshToWorldMatrix, [-0.0,-2.0,-7.5]);
const t = TIME * 1000;
rotationMat(MeshToWorldRotMatrix, TIME * 20, 1);)");
  const auto projection = course::projection_of(named);
  ASSERT_TRUE(projection);
  EXPECT_EQ(projection->fov_y_degrees, 45.0);
  EXPECT_EQ(projection->near, 0.1);
  EXPECT_EQ(projection->far, 100.0);
  const auto at = course::mesh_translation_of(named);
  ASSERT_TRUE(at);
  EXPECT_EQ(*at, (std::array{0.0, -2.0, -7.5}));
  EXPECT_FALSE(std::signbit((*at)[0])) << "-0.0 is 0 in a profile";
  EXPECT_EQ(course::degrees_per_second_of(named), 20.0) << "the rotation's factor, not TIME * 1000 elsewhere";

  const course::ScriptFacts radians(R"(const SPEED = 15;
mat4.perspective(P, 30 * Math.PI / 180, 1.0, 0.5, 20.0);
mat4.translate(M, M, [1.5, -0.0, -9]);
const angle = SPEED * TIME;)");
  EXPECT_NEAR(course::projection_of(radians)->fov_y_degrees, 30.0, 1e-9) << "an expression in radians, with a literal aspect";
  EXPECT_EQ(course::projection_of(radians)->near, 0.5);
  EXPECT_EQ(*course::mesh_translation_of(radians), (std::array{1.5, 0.0, -9.0}));
  EXPECT_EQ(course::degrees_per_second_of(radians), 15.0) << "a named factor before TIME, outside any call";

  const course::ScriptFacts silent("const proj = perspective(fov, aspect, near, far);\nrotateY(angle);");
  EXPECT_FALSE(course::projection_of(silent)) << "names bound nowhere: not stated";
  EXPECT_FALSE(course::mesh_translation_of(silent));
  EXPECT_FALSE(course::degrees_per_second_of(silent));
}

// `course import` on a folder written in the course's own style (named constants passed to the
// matrix helpers, the factor after TIME, a negative zero), for this test: every fact found, none
// assumed; the same folder with other values: those values.
TEST(CourseImportStyleTest, NamedConstantsAndTheFactorAfterTimeAreFoundNotAssumed) {
  const fs::path root = fs::temp_directory_path() / ("shadelab_import_style_" + std::to_string(::getpid()));
  const auto import = [&](double fov, const std::string& at, double spin) {
    fs::remove_all(root);
    write(root / "HW2/index.html", "<canvas id=\"glcanvas\" width=\"512\" height=\"512\"></canvas>\n");
    std::ostringstream js;
    js << "const fieldOfView = " << fov << ";\nconst zNear = 0.1;\nconst zFar = 100.0;\n"
       << "const uniformValues = { uAmbientColor: [0.2, 0.1, 0.1, 1.0] };\n"
       << "function draw() {\n  mat4Perspective(ProjectionMatrix, fieldOfView, canvas.width / canvas.height, zNear, zFar);\n"
       << "  mat4Translate(MeshToWorldMatrix, " << at << ");\n  rotationMat(MeshToWorldRotMatrix, TIME * " << spin << ", 1);\n}\n";
    write(root / "HW2/src/hw2.js", js.str());
    auto imported = course::import_course({root / "HW2", std::nullopt, root / "course.json", "style", ""});
    EXPECT_TRUE(imported) << imported.error().message;
    return imported ? *imported : course::ImportedCourse{};
  };
  const auto said = [](const std::vector<std::string>& lines, const std::string& start) {
    return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.rfind(start, 0) == 0; });
  };

  auto course = import(45.0, "[-0.0,-2.0,-7.5]", 20);
  EXPECT_EQ(course.profile["camera"]["fovYDegrees"], 45.0);
  EXPECT_EQ(course.profile["camera"]["near"], 0.1);
  EXPECT_EQ(course.profile["camera"]["far"], 100.0);
  EXPECT_EQ(course.profile["camera"]["meshTranslation"].dump(), "[0.0,-2.0,-7.5]");
  EXPECT_EQ(course.profile["frames"]["degreesPerFrame"], 20.0);
  for (const char* fact : {"camera:", "the mesh stands at", "the mesh turns"}) {
    EXPECT_TRUE(said(course.found, fact)) << fact;
    EXPECT_FALSE(said(course.assumed, fact)) << fact;
  }

  course = import(30.0, "[1.0, -0.0, -9.0]", 15);
  EXPECT_EQ(course.profile["camera"]["fovYDegrees"], 30.0);
  EXPECT_EQ(course.profile["camera"]["meshTranslation"].dump(), "[1.0,0.0,-9.0]");
  EXPECT_EQ(course.profile["frames"]["degreesPerFrame"], 15.0);
  fs::remove_all(root);
}

// A homework folder laid out as the course's (index.html, src/hw2.js, src/shaders/, assets/), its
// facts all different from the built-in course's, written for this test; a solution folder with
// the TA's solved normals pair.
class CourseImportTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(fs::temp_directory_path() / ("shadelab_course_import_" + std::to_string(::getpid())));
    const fs::path hw = *root_ / "HW2";
    write(hw / "index.html", "<!doctype html>\n<title>Graphics 101 HW2</title>\n<canvas id=\"glcanvas\" width=400px height=300px></canvas>\n"
                             "<script type=\"module\" src=\"src/hw2.js\"></script>\n");
    write(hw / "src/hw2.js", R"(const IMAGE_PREFIX = "normals";
const MAX_OUT_FRAMES = 0;
const OBJ_FILE = "assets/teapot.obj";
const uniformValues = {
    uAmbient: [0.1, 0.0, 0.2, 1.0],
    uDiffuse: new Float32Array([0.3, 0.6, 0.9, 1.0]),
    uSpecular: [1.0, 1.0, 1.0, 1.0],
    uLightPos: [-8.0, 10.0, 6.0],
    uLightCol: [0.9, 0.9, 0.8, 1.0],
};
function setUp(gl, program) {
    const ambient = gl.getUniformLocation(program, "uAmbient");
    const light = gl.getUniformLocation(program, "uLightPos");
    const lightColour = gl.getUniformLocation(program, "uLightCol");
    // TODO: diffuse and specular
}
function draw(gl) {
    const gl_ = gl.getContext ? gl.getContext("webgl2") : gl;
    const proj = perspective(60 * Math.PI / 180, width / height, 0.5, 50.0);
    const world = translate(identity(), [0.0, -1.5, -6.0]);
    const spin = rotateY(30 * TIME);
    const name = `hw2_${IMAGE_PREFIX}_${frame}.png`;
}
)");
    const auto preset = [](const std::string& name, const std::string& stage) {
      return testkit::read_text(kSource / "shaders" / (name + "_" + stage + ".js"));
    };
    write(hw / "src/shaders/starter_vert.js", preset("starter", "vert"));
    write(hw / "src/shaders/starter_frag.js", preset("starter", "frag"));
    write(hw / "src/shaders/phong_vert.js", preset("specular", "vert"));
    // The folder's phong reads the uniforms under the names its hw2.js feeds.
    std::string phong = preset("specular", "frag");
    for (const auto& [builtin, here] : {std::pair{"uAmbientColor", "uAmbient"}, {"uDiffuseColor", "uDiffuse"},
                                        {"uSpecularColor", "uSpecular"}, {"uLightPosition", "uLightPos"}, {"uLightColor", "uLightCol"}})
      for (size_t at; (at = phong.find(builtin)) != std::string::npos;) phong.replace(at, std::strlen(builtin), here);
    phong.replace(phong.find("float specularAlpha = 6.0;"), 26, "float specularAlpha = 10.0;");
    write(hw / "src/shaders/phong_frag.js", phong);
    fs::create_directories(hw / "assets");
    fs::copy_file(kSource / "assets/teapot.obj", hw / "assets/teapot.obj");
    write(*root_ / "solution/starter_vert.js", preset("normals", "vert"));
    write(*root_ / "solution/starter_frag.js", preset("normals", "frag"));
    imported_ = run_cli("course import " + hw.string() + " --solution " + (*root_ / "solution").string() + " --id graphics101 -o " +
                        (*root_ / "profile/course.json").string());
  }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete root_;
  }
  void SetUp() override { ASSERT_EQ(imported_.status, 0) << imported_.output; }
  static json profile() { return json::parse(testkit::read_text(*root_ / "profile/course.json")); }
  static fs::path* root_;
  static CliRun imported_;
};
fs::path* CourseImportTest::root_ = nullptr;
CliRun CourseImportTest::imported_;

TEST_F(CourseImportTest, TheFolderGivesTheCanvasValuesCameraMeshesAndExponent) {
  const json p = profile();
  EXPECT_EQ(p["id"], "graphics101");
  EXPECT_EQ(p["canvas"], json({{"width", 400}, {"height", 300}}));
  const auto uniform = [&](const std::string& role) {
    for (const auto& u : p["uniforms"])
      if (u["role"] == role) return u;
    return json();
  };
  EXPECT_EQ(uniform("ambient")["names"], json({"uAmbient", "ambient"})) << "both spellings the handout allows";
  EXPECT_EQ(uniform("ambient")["value"], json({0.1, 0.0, 0.2, 1.0}));
  EXPECT_EQ(uniform("diffuse")["names"], json({"uDiffuse", "diffuse"})) << "the students' TODO, named as the page names ambient";
  EXPECT_EQ(uniform("diffuse")["value"], json({0.3, 0.6, 0.9, 1.0}));
  EXPECT_EQ(uniform("lightPosition")["value"], json({-8.0, 10.0, 6.0}));
  EXPECT_EQ(uniform("lightColor")["names"], json({"uLightCol", "lightCol"}));
  EXPECT_EQ(p["camera"]["fovYDegrees"], 60.0);
  EXPECT_EQ(p["camera"]["near"], 0.5);
  EXPECT_EQ(p["camera"]["far"], 50.0);
  EXPECT_EQ(p["camera"]["meshTranslation"], json({0.0, -1.5, -6.0}));
  EXPECT_EQ(p["frames"]["degreesPerFrame"], 30.0);
  EXPECT_EQ(p["frames"]["fileName"], "hw2_{prefix}_{k}");
  EXPECT_EQ(p["specularExponent"]["value"], 10.0);
  EXPECT_EQ(p["meshes"], json::array({{{"name", "teapot"}, {"file", "../HW2/assets/teapot.obj"}}}));
  EXPECT_EQ(p["defaultMesh"], "teapot");
  const std::string& out = imported_.output;
  for (const char* said : {"found: canvas 400 x 300 (index.html)", "found: the starter's exponent: specularAlpha = 10.0 (src/shaders/phong_frag.js)",
                           "assumed: frames: 9 (MAX_OUT_FRAMES is 0 or absent; the notebook's 3 x 3 grid)",
                           "assumed: diffuse is named uDiffuse (hw2.js does not look it up: the students' TODO)",
                           "found: the normals reference (the solution's starter)",
                           "assumed: the specular reference: the built-in course's with specularAlpha = 10.0, written to course.specular_frag.js"})
    EXPECT_NE(out.find(said), std::string::npos) << said << "\n" << out;
  EXPECT_EQ(out.find("mistake specular/flat_shading left out"), std::string::npos) << "the built-in reference's edits apply";
  EXPECT_TRUE(fs::exists(*root_ / "profile/course.specular_frag.js"));
  // The built-in references read the uniforms under the names this page feeds (else: all zero, black).
  for (const char* file : {"profile/course.specular_frag.js", "profile/course.diffuse_frag.js"}) {
    const std::string text = testkit::read_text(*root_ / file);
    EXPECT_NE(text.find("uniform vec3 uLightPos;"), std::string::npos) << file;
    EXPECT_EQ(text.find("uLightPosition"), std::string::npos) << file;
  }
  EXPECT_EQ(p["checkpoints"][2]["mistakes"][4]["edits"][0]["find"], "uDiffuse * uLightCol * max(0.0, NdotL)") << "the edits take the names too";
  // The handout's-exponent mistake follows the folder's exponent.
  const json& handout = p["checkpoints"][2]["mistakes"][5];
  ASSERT_EQ(handout["id"], "handout_exponent");
  EXPECT_EQ(handout["edits"][0]["find"], "float specularAlpha = 10.0;");
  EXPECT_NE(handout["message"].get<std::string>().find("the course's starter uses 10.0"), std::string::npos) << handout;
  // The folder's starter is what its students received: public; the solution's are references.
  for (const auto& preset : p["presets"]) EXPECT_EQ(preset.value("public", false), preset["name"] == "starter") << preset;
  EXPECT_NE(imported_.output.find("students see: starter; references, staff only: smooth normals diffuse specular"), std::string::npos)
      << imported_.output;
}

TEST_F(CourseImportTest, TheImportedCourseRendersAndGradesWithItsCanvasAndLightOnTheCommandLine) {
  const std::string course = " --course " + (*root_ / "profile/course.json").string();
  auto run = run_cli("render --preset diffuse --grid " + (*root_ / "g.png").string() + course);
  ASSERT_EQ(run.status, 0) << run.output;
  const auto grid = testkit::decode(bytes_of(testkit::read_text(*root_ / "g.png")));
  EXPECT_EQ(grid.width, 3 * 400);
  EXPECT_EQ(grid.height, 3 * 300);
  // The same pair under the built-in course's light and colours is another image: the profile's
  // values reached the render.
  run = run_cli("render --preset diffuse --size 400x300 --grid " + (*root_ / "b.png").string());
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(testkit::read_text(*root_ / "g.png"), testkit::read_text(*root_ / "b.png"));
  // The folder's own phong with its exponent passes its specular checkpoint (against the built-in
  // reference in this course's uniform names); with the built-in course's 6.0 it does not, and says why.
  const fs::path hw = *root_ / "HW2/src/shaders";
  const std::string result = " -o " + (*root_ / "grade.json").string();
  run = run_cli("grade --vert " + (hw / "phong_vert.js").string() + " --frag " + (hw / "phong_frag.js").string() + course +
                " --reference specular --size 100x75" + result);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_TRUE(json::parse(testkit::read_text(*root_ / "grade.json"))["pass"]) << run.output;
  std::string six = testkit::read_text(hw / "phong_frag.js");
  six.replace(six.find("float specularAlpha = 10.0;"), 27, "float specularAlpha = 6.0;");
  write(*root_ / "six_frag.js", six);
  run = run_cli("grade --vert " + (hw / "phong_vert.js").string() + " --frag " + (*root_ / "six_frag.js").string() + course +
                " --reference specular --size 100x75");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("your shader's exponent is 6.0; the course's starter uses 10.0"), std::string::npos) << run.output;
}

TEST_F(CourseImportTest, AServerHoldingBothCoursesRendersAndGradesEachByItsId) {
  auto imported = course::load_course_file(*root_ / "profile/course.json");
  ASSERT_TRUE(imported) << imported.error().message;
  auto config = testkit::test_config();
  auto set = course::CourseSet::of({std::shared_ptr<const course::Course>(&course::builtin_course(), [](const course::Course*) {}),
                                    std::make_shared<course::Course>(std::move(*imported))});
  ASSERT_TRUE(set);
  config.courses = std::move(*set);
  testkit::RunningService server(std::move(config));
  ASSERT_TRUE(server.ok()) << server.failure;
  auto listed = server.client().Get("/api/courses");
  ASSERT_TRUE(listed);
  EXPECT_EQ(json::parse(listed->body)["courses"].size(), 2u);
  testkit::expect_conforms(*listed, "/api/courses", "get");
  auto page = server.client().Get("/api/course?course=graphics101");
  ASSERT_TRUE(page);
  ASSERT_EQ(page->status, 200) << page->body;
  EXPECT_EQ(json::parse(page->body)["canvas"]["width"], 400);
  testkit::expect_conforms(*page, "/api/course", "get");
  auto builtin = server.client().Get("/api/course");
  ASSERT_TRUE(builtin);
  EXPECT_EQ(json::parse(builtin->body)["id"], course::builtin_course().id) << "the first course is the default";
  auto mesh = server.client().Get("/api/meshes/teapot.obj?course=graphics101");
  ASSERT_TRUE(mesh);
  EXPECT_EQ(mesh->body, testkit::read_text(*root_ / "HW2/assets/teapot.obj")) << "the course's own file, as its page loads it";
  auto r = server.client().Post("/api/render", json{{"course", "graphics101"}, {"preset", "specular"}, {"output", "json"}}.dump(), "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const json rendered = json::parse(r->body);
  EXPECT_EQ(rendered["images"]["frames"][0]["name"], "hw2_specular_0.png");
  const auto frame = testkit::decode(bytes_of(*base64_decode(rendered["images"]["frames"][0]["data"].get<std::string>())));
  EXPECT_EQ(frame.width, 400);
  EXPECT_EQ(frame.height, 300);
  const fs::path hw = *root_ / "HW2/src/shaders";
  auto g = server.client().Post("/api/grade",
                                json{{"course", "graphics101"}, {"reference", "specular"}, {"vertex", testkit::read_text(hw / "phong_vert.js")},
                                     {"fragment", testkit::read_text(hw / "phong_frag.js")}, {"width", 100}, {"height", 75}}
                                    .dump(),
                                "application/json");
  ASSERT_TRUE(g);
  ASSERT_EQ(g->status, 200) << g->body;
  EXPECT_TRUE(json::parse(g->body)["pass"]) << g->body;
  auto unknown = server.client().Post("/api/render", json{{"course", "cs999"}, {"preset", "specular"}}.dump(), "application/json");
  ASSERT_TRUE(unknown);
  EXPECT_EQ(unknown->status, 404);
  EXPECT_NE(unknown->body.find("unknown_course"), std::string::npos);
  testkit::expect_conforms(*unknown, "/api/render", "post");
  EXPECT_NE(unknown->body.find("it holds: cs148-summer2022, graphics101"), std::string::npos) << unknown->body;
}
