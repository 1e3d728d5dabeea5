// Who may see what (course/access.h), against the real server with its default setting: every
// route of the OpenAPI document called as a student answers without a reference's source (any line
// of it the starter does not share) or a reference's pixels (checked against the reference's own
// render, fetched with a staff key), in its body and its headers; a staff key sees the references.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/base64.h"
#include "course/course_reader.h"
#include "course/course_set.h"
#include "image/png_decode.h"
#include "support/files.h"
#include "support/http_fixture.h"
#include "support/openapi_check.h"
#include "support/test_support.h"

namespace shadelab::testkit {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

const std::string kStaff = "staff-0123456789abcdef", kStudent = "student-0123456789ab";
const std::string kRightLine = "vec3 L = normalize(uLightPosition - vPosition);";  // the specular reference's line 20

httplib::Headers bearer(const std::string& key) { return {{"Authorization", "Bearer " + key}}; }

// Lines of the references' source a student must never be shown: each line of a reference shader
// at least 24 characters long, trimmed, that no public preset has.
std::vector<std::string> secret_lines() {
  const course::Course& c = course();
  std::string public_text;
  for (const auto& p : c.presets)
    if (p.is_public) public_text += p.vertex.text + "\n" + p.fragment.text + "\n";
  std::set<std::string> out;
  for (const auto& p : c.presets) {
    if (p.is_public) continue;
    for (const std::string* text : {&p.vertex.text, &p.fragment.text}) {
      std::istringstream lines(*text);
      for (std::string line; std::getline(lines, line);) {
        const auto first = line.find_first_not_of(" \t"), last = line.find_last_not_of(" \t\r");
        if (first == std::string::npos) continue;
        line = line.substr(first, last - first + 1);
        if (line.size() >= 24 && public_text.find(line) == std::string::npos) out.insert(line);
      }
    }
  }
  return {out.begin(), out.end()};
}

// Every PNG a response carries: whole in its bytes (an image body, a stored zip's entries), in a
// JSON string in base64, or in an HTML data URI.
void pngs_in_bytes(const std::string& bytes, std::vector<std::string>& out) {
  static const std::string kSignature = "\x89PNG\r\n\x1a\n";
  for (size_t at = bytes.find(kSignature); at != std::string::npos; at = bytes.find(kSignature, at + 1)) {
    size_t end = at + kSignature.size();
    while (end + 12 <= bytes.size()) {
      const auto byte = [&](size_t i) { return static_cast<size_t>(static_cast<unsigned char>(bytes[i])); };
      const size_t length = byte(end) << 24 | byte(end + 1) << 16 | byte(end + 2) << 8 | byte(end + 3);
      const std::string type = bytes.substr(end + 4, 4);
      end += 12 + length;
      if (type == "IEND") {
        out.push_back(bytes.substr(at, end - at));
        break;
      }
    }
  }
}
void pngs_in_json(const json& j, std::vector<std::string>& out) {
  if (j.is_string() && j.get_ref<const std::string&>().size() > 64) {
    if (auto decoded = base64_decode(j.get<std::string>())) pngs_in_bytes(*decoded, out);
  }
  if (j.is_structured())
    for (const auto& item : j) pngs_in_json(item, out);
}
std::vector<std::string> pngs_in(const httplib::Response& r) {
  std::vector<std::string> out;
  pngs_in_bytes(r.body, out);
  if (const json j = json::parse(r.body, nullptr, false); !j.is_discarded()) pngs_in_json(j, out);
  for (size_t at = r.body.find("base64,"); at != std::string::npos; at = r.body.find("base64,", at + 1)) {
    const size_t end = r.body.find_first_of("\"' )", at + 7);
    if (auto decoded = base64_decode(r.body.substr(at + 7, end - at - 7))) pngs_in_bytes(*decoded, out);
  }
  return out;
}

std::string headers_text(const httplib::Response& r) {
  std::string out;
  for (const auto& [k, v] : r.headers) out += k + ": " + v + "\n";
  return out;
}

// The bunny rendered in the course's colours, the purple question's answer: with the reference's
// shaders, the reference's own frame 0.
const char* kNotebookWithTheCoursesColours = R"nb({"nbformat": 4, "cells": [
  {"cell_type": "markdown", "source": "Which ambient, diffuse and specular colours make a purple bunny with blue-ish highlights?"},
  {"cell_type": "markdown", "source": "Ambient (0.2, 0.1, 0.1); diffuse (0.7, 0.5, 0.1); specular (0.1, 0.4, 0.8)"}]})nb";

struct Call {
  std::string method, route;  // as the OpenAPI document names it
  std::function<httplib::Result(httplib::Client&, const httplib::Headers&)> send;
};

class AccessTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    keys_ = new fs::path(fs::temp_directory_path() / ("shadelab_access_keys_" + std::to_string(::getpid())));
    std::ofstream(*keys_) << "# a class's keys\n" << kStaff << " ta1 staff\n" << kStudent << " alice\n";
    auto config = test_config();
    config.open_references = false;  // the default a server starts with
    config.tenants.api_keys_file = keys_->string();
    server_ = new RunningService(config);
    references_ = new std::vector<image::Image>();
    if (!server_->ok()) return;
    auto c = server_->client();
    for (const auto& p : course().presets) {
      if (p.is_public) continue;
      auto r = c.Get(("/api/render?output=json&preset=" + p.name).c_str(), bearer(kStaff));
      if (!r || r->status != 200) continue;
      for (const auto& png : pngs_in(*r))
        if (auto image = image::decode_png(png)) references_->push_back(std::move(*image));
    }
  }
  static void TearDownTestSuite() {
    delete server_;
    delete references_;
    fs::remove(*keys_);
    delete keys_;
  }
  void SetUp() override { ASSERT_TRUE(server_->ok()) << server_->failure; }

  // Nothing of a reference in `r`: its source in the body or a header, or its pixels in an image.
  static void expect_nothing_of_a_reference(const httplib::Response& r, const std::string& what) {
    const std::string text = r.body + "\n" + headers_text(r);
    for (const auto& line : secret_lines()) EXPECT_EQ(text.find(line), std::string::npos) << what << " quotes a reference: " << line;
    for (const auto& png : pngs_in(r)) {
      auto image = image::decode_png(png);
      if (!image) continue;
      for (const auto& reference : *references_)
        EXPECT_FALSE(image->width == reference.width && image->height == reference.height && image->bytes == reference.bytes)
            << what << " carries a reference's frame";
    }
  }

  static fs::path* keys_;
  static RunningService* server_;
  static std::vector<image::Image>* references_;
};
fs::path* AccessTest::keys_ = nullptr;
RunningService* AccessTest::server_ = nullptr;
std::vector<image::Image>* AccessTest::references_ = nullptr;

std::string shader_text(const std::string& preset, const std::string& stage) {
  const auto* p = course().preset(preset);
  return stage == "vertex" ? p->vertex.text : p->fragment.text;
}

// The calls a student makes, at least one for every route and method the document has.
std::vector<Call> student_calls() {
  const auto get = [](std::string route, std::string url) {
    return Call{"get", route, [url](httplib::Client& c, const httplib::Headers& h) { return c.Get(url.c_str(), h); }};
  };
  const auto post = [](std::string route, std::string url, json body) {
    return Call{"post", route, [url, body](httplib::Client& c, const httplib::Headers& h) {
                  return c.Post(url.c_str(), h, body.dump(), "application/json");
                }};
  };
  const json starter = {{"vertex", shader_text("starter", "vertex")}, {"fragment", shader_text("starter", "fragment")}};
  json starter_json = starter;
  starter_json["output"] = "json";
  json graded = starter;
  graded["reference"] = "specular";
  json graded_gradescope = graded;
  graded_gradescope["format"] = "gradescope";
  const json sheet = {{"format", "html"},
                      {"files", {{"src/shaders/starter_vert.js", shader_text("starter", "vertex")},
                                 {"src/shaders/starter_frag.js", shader_text("starter", "fragment")},
                                 {"HW2.ipynb", kNotebookWithTheCoursesColours}}}};
  std::vector<Call> calls = {
      get("/api/presets", "/api/presets"),
      get("/api/course", "/api/course"),
      get("/api/courses", "/api/courses"),
      get("/api/render", "/api/render?preset=specular&output=frames"),
      get("/api/render", "/api/render?preset=diffuse"),
      get("/api/render", "/api/render?preset=normals&output=json"),
      get("/api/render", "/api/render?preset=starter&output=json"),
      post("/api/render", "/api/render", {{"preset", "specular"}, {"output", "json"}}),
      post("/api/render", "/api/render", starter_json),
      post("/api/compile", "/api/compile", {{"preset", "specular"}}),
      post("/api/compile", "/api/compile", starter),
      post("/api/grade", "/api/grade", graded),
      post("/api/grade", "/api/grade", graded_gradescope),
      post("/api/grade", "/api/grade", {{"preset", "specular"}, {"reference", "specular"}}),
      post("/api/sheet", "/api/sheet", sheet),
      get("/api/meshes", "/api/meshes"),
      {"post", "/api/meshes", [](httplib::Client& c, const httplib::Headers& h) {
         return c.Post("/api/meshes?filename=tri.obj", h, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "text/plain");
       }},
      get("/api/meshes/{name}.obj", "/api/meshes/bunny.obj"),
      get("/api/scenes", "/api/scenes"),
      get("/api/scenes/{name}", "/api/scenes/two_objects"),
      get("/api/dolly", "/api/dolly?lens=25"),
      get("/api/openapi.json", "/api/openapi.json"),
      post("/api/session", "/api/session", json::object()),
      get("/api/session", "/api/session"),
      post("/api/session/end", "/api/session/end", json::object()),
      get("/livez", "/livez"),
      get("/readyz", "/readyz"),
      get("/metrics", "/metrics"),
  };
  calls.push_back({"post", "/api/scene", [](httplib::Client& c, const httplib::Headers& h) {
                     auto scene = c.Get("/api/scenes/two_objects", h);
                     return c.Post("/api/scene?format=json", h, scene ? scene->body : "{}", "application/json");
                   }});
  return calls;
}

TEST_F(AccessTest, TheTestHasTheReferencesToLookForAndCallsEveryDocumentedRoute) {
  size_t references = 0;
  for (const auto& p : course().presets) references += !p.is_public;
  EXPECT_EQ(references_->size(), references * (course().frames + 1)) << "each reference's frames and grid, fetched with the staff key";
  EXPECT_GT(secret_lines().size(), 10u);
  std::set<std::string> called, documented;
  for (const auto& call : student_calls()) called.insert(call.method + " " + call.route);
  for (const auto& [path, methods] : openapi()["paths"].items())
    for (const auto& [method, op] : methods.items()) documented.insert(method + " " + path);
  EXPECT_EQ(called, documented);
}

// With a student's key, and on a server with no keys at all.
TEST_F(AccessTest, NoRouteGivesAStudentAReferencesSourceOrPixels) {
  auto c = server_->client();
  for (const auto& call : student_calls()) {
    auto r = call.send(c, bearer(kStudent));
    ASSERT_TRUE(r) << call.method << " " << call.route;
    EXPECT_LT(r->status, 500) << call.method << " " << call.route << ": " << r->body.substr(0, 300);
    expect_nothing_of_a_reference(*r, call.method + " " + call.route);
  }
}

// A class server whose students need no key (serve --api-keys FILE --students-without-keys): a
// caller without a key is a student on every route, a staff key still sees the references, and a
// key the file does not hold is refused, never taken for a student's absence of one.
// A failing grade's repair (road/repair_search.h): a student reads what is wrong and where, never
// the repaired line (which is the reference's line, however short: the rule above that looks for
// the references' lines of 24 characters or more would miss `N = normalize(N);`); a staff key
// reads it too.
// The specular reference with L left unnormalised at phong_frag.js line 20: a mistake the formula
// does not explain and the repair search does. `course`: the id of the course to grade it in.
json unnormalised_light(const std::string& course = "") {
  std::string fragment = shader_text("specular", "fragment");
  fragment.replace(fragment.find(kRightLine), kRightLine.size(), "vec3 L = uLightPosition - vPosition;");
  json job = {{"vertex", shader_text("specular", "vertex")}, {"fragment", fragment}, {"vertexName", "phong_vert.js"},
              {"fragmentName", "phong_frag.js"}, {"width", 96}, {"height", 96}, {"reference", "specular"}};
  if (!course.empty()) job["course"] = course;
  return job;
}

// The report of `job` graded over HTTP with `key`; a student's never holds the repaired line.
json graded(testkit::RunningService& server, const json& job, const std::string& key) {
  const auto r = server.client().Post("/api/grade", bearer(key), job.dump(), "application/json");
  EXPECT_TRUE(r && r->status == 200) << (r ? r->body : "no response");
  if (!r || r->status != 200) return json::object();
  if (key == kStudent) {
    EXPECT_EQ(r->body.find("normalize(uLightPosition - vPosition)"), std::string::npos) << "a student was given the repaired line";
  }
  return json::parse(r->body);
}

TEST_F(AccessTest, AStudentReadsWhereARepairIsAndNeverTheRepairedLine) {
  for (const auto& key : {kStudent, kStaff}) {
    const json report = graded(*server_, unnormalised_light(), key);
    EXPECT_FALSE(report["pass"]);
    const json& found = report["repairSearch"]["found"];
    ASSERT_TRUE(found.is_object()) << report.dump();
    EXPECT_EQ(found["kind"], "normalised");
    EXPECT_EQ(found["file"], "phong_frag.js");
    EXPECT_EQ(found["line"], 20);
    const std::string said = report["messages"].dump();
    EXPECT_NE(said.find("phong_frag.js line 20: `L` is not normalised"), std::string::npos) << said;
    EXPECT_EQ(said.find("cannot say why"), std::string::npos) << "a confirmed repair is not 'cannot say why': " << said;
    if (key == kStaff) {
      EXPECT_EQ(found["repairedLine"], kRightLine);
    } else {
      EXPECT_FALSE(found.contains("repairedLine")) << report.dump();
    }
  }
  // A class batch through --server grades with a staff key for its students: asked to answer as a
  // student is, the server keeps the repaired line to itself.
  httplib::Headers as_student = bearer(kStaff);
  as_student.emplace("X-ShadeLab-View", "student");
  const auto r = server_->client().Post("/api/grade", as_student, unnormalised_light().dump(), "application/json");
  ASSERT_TRUE(r && r->status == 200);
  EXPECT_EQ(r->body.find("normalize(uLightPosition - vPosition)"), std::string::npos) << r->body.substr(0, 400);
  EXPECT_NE(r->body.find("phong_frag.js line 20: `L` is not normalised"), std::string::npos);
}

// A course says how much of a repair its students read (the profile's `repairShown`): what is
// wrong alone, or the repaired line too; staff read the repaired line in every course.
TEST_F(AccessTest, HowMuchOfARepairAStudentReadsIsTheirCoursesChoice) {
  std::vector<std::shared_ptr<const course::Course>> courses = {
      std::shared_ptr<const course::Course>(&course::builtin_course(), [](const course::Course*) {})};
  for (const auto& [id, shown] : {std::pair{"shown-what", "what"}, std::pair{"shown-line", "repairedLine"}}) {
    json profile = course::to_json(course::builtin_course());
    profile["id"] = id;
    profile["repairShown"] = shown;
    auto read = course::read_course(profile.dump(), course::embedded_source("courses"), "test.json");
    ASSERT_TRUE(read) << read.error().message;
    courses.push_back(std::make_shared<course::Course>(std::move(*read)));
  }
  auto set = course::CourseSet::of(std::move(courses));
  ASSERT_TRUE(set);
  auto config = test_config();
  config.open_references = false;
  config.tenants.api_keys_file = keys_->string();
  config.courses = std::move(*set);
  RunningService server(config);
  ASSERT_TRUE(server.ok()) << server.failure;

  const json what = graded(server, unnormalised_light("shown-what"), kStudent);
  const json& said_what = what["repairSearch"]["found"];
  ASSERT_TRUE(said_what.is_object()) << what.dump();
  EXPECT_FALSE(said_what.contains("file") || said_what.contains("line") || said_what.contains("repairedLine")) << said_what.dump();
  const std::string messages = what["messages"].dump();
  EXPECT_NE(messages.find("`L` is not normalised"), std::string::npos) << messages;
  EXPECT_EQ(messages.find("line 20"), std::string::npos) << "the course shows what is wrong, not where: " << messages;
  EXPECT_EQ(graded(server, unnormalised_light("shown-what"), kStaff)["repairSearch"]["found"]["repairedLine"], kRightLine);

  const auto r = server.client().Post("/api/grade", bearer(kStudent), unnormalised_light("shown-line").dump(), "application/json");
  ASSERT_TRUE(r && r->status == 200) << (r ? r->body : "no response");
  const json line = json::parse(r->body);
  EXPECT_EQ(line["repairSearch"]["found"]["repairedLine"], kRightLine) << "the course shows its students the repaired line";
  EXPECT_EQ(line["repairSearch"]["found"]["line"], 20);
  EXPECT_NE(line["messages"].dump().find("With `" + kRightLine + "`"), std::string::npos) << line["messages"].dump();
}

TEST_F(AccessTest, WithStudentsWithoutKeysACallerWithoutAKeyIsAStudentOnEveryRoute) {
  auto config = test_config();
  config.open_references = false;
  config.tenants.api_keys_file = keys_->string();
  config.tenants.students_without_keys = true;
  RunningService keyless(config);
  ASSERT_TRUE(keyless.ok()) << keyless.failure;
  auto c = keyless.client();
  for (const auto& call : student_calls()) {
    auto r = call.send(c, {});
    ASSERT_TRUE(r) << call.method << " " << call.route;
    EXPECT_NE(r->status, 401) << call.method << " " << call.route;
    EXPECT_LT(r->status, 500) << call.method << " " << call.route << ": " << r->body.substr(0, 300);
    expect_nothing_of_a_reference(*r, call.method + " " + call.route + " without a key");
  }
  const json as_student = json::parse(c.Get("/api/course")->body);
  EXPECT_EQ(as_student["viewer"]["role"], "student");
  auto refused = c.Get("/api/render?preset=specular");
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 403);
  const json as_staff = json::parse(c.Get("/api/course", bearer(kStaff))->body);
  EXPECT_EQ(as_staff["viewer"]["role"], "staff");
  auto staff_render = c.Get("/api/render?preset=specular&width=32&height=24", bearer(kStaff));
  ASSERT_TRUE(staff_render);
  EXPECT_EQ(staff_render->status, 200);
  auto unknown = c.Get("/api/presets", bearer("staff-0123456789abcdeX"));
  ASSERT_TRUE(unknown);
  EXPECT_EQ(unknown->status, 401) << "an unknown key is refused, not read as a student";
}

TEST_F(AccessTest, AReferenceAskedForByAStudentIsRefusedNamingWhatTheyMayUse) {
  auto c = server_->client();
  for (const char* url : {"/api/render?preset=specular&output=frames", "/api/render?preset=gouraud"}) {
    auto r = c.Get(url, bearer(kStudent));
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 403) << url << ": " << r->body;
    const json p = json::parse(r->body);
    EXPECT_EQ(p["code"], "reference_private");
    EXPECT_NE(p["detail"].get<std::string>().find("Students may render starter"), std::string::npos) << p["detail"];
    expect_conforms(*r, "/api/render", "get");
  }
  auto presets = c.Get("/api/presets", bearer(kStudent));
  ASSERT_TRUE(presets);
  const json listed = json::parse(presets->body);
  ASSERT_EQ(listed.size(), 1u) << presets->body;
  EXPECT_EQ(listed[0]["name"], "starter");
  EXPECT_EQ(listed[0]["vertex"]["source"], shader_text("starter", "vertex"));
  const json course_json = json::parse(c.Get("/api/course", bearer(kStudent))->body);
  EXPECT_EQ(course_json["pagePreset"], "starter");
  EXPECT_EQ(course_json["defaultPreset"], "starter");
  EXPECT_EQ(course_json["viewer"]["role"], "student");
  EXPECT_EQ(course_json["viewer"]["seesReferences"], false);
}

TEST_F(AccessTest, AStaffKeySeesTheReferences) {
  auto c = server_->client();
  auto presets = c.Get("/api/presets", bearer(kStaff));
  ASSERT_TRUE(presets);
  const json listed = json::parse(presets->body);
  ASSERT_EQ(listed.size(), course().presets.size());
  for (const auto& p : listed) EXPECT_EQ(p["fragment"]["source"], shader_text(p["name"], "fragment")) << p["name"];
  const json course_json = json::parse(c.Get("/api/course", bearer(kStaff))->body);
  EXPECT_EQ(course_json["viewer"]["role"], "staff");
  EXPECT_EQ(course_json["defaultPreset"], course().default_preset);
  EXPECT_EQ(course_json["pagePreset"], "starter");  // the page opens as the course's does, for anyone
  auto render = c.Get("/api/render?preset=specular&output=frames", bearer(kStaff));
  ASSERT_TRUE(render);
  EXPECT_EQ(render->status, 200);
}

// Where the course wants frames saved from its page, ShadeLab's frame downloads say what they are for.
TEST_F(AccessTest, AFramesDownloadSaysItIsForCheckingNotForHandingIn) {
  auto c = server_->client();
  auto r = c.Get("/api/render?preset=starter&output=frames&width=32&height=24", bearer(kStudent));
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_NE(r->get_header_value("X-ShadeLab-Notice").find("for checking, not for handing in"), std::string::npos);
  EXPECT_NE(r->body.find("FOR_CHECKING_NOT_FOR_HANDING_IN.txt"), std::string::npos);
  EXPECT_NE(r->body.find("for checking, not for handing in"), std::string::npos);
  auto grid = c.Get("/api/render?preset=starter&width=32&height=24", bearer(kStudent));
  ASSERT_TRUE(grid);
  EXPECT_FALSE(grid->has_header("X-ShadeLab-Notice")) << "the grid is no hand-in";
}

// A server without keys: every caller is a student.
TEST(AccessWithoutKeysTest, EveryCallerIsAStudent) {
  auto config = test_config();
  config.open_references = false;
  RunningService server(config);
  ASSERT_TRUE(server.ok()) << server.failure;
  auto c = server.client();
  auto presets = c.Get("/api/presets");
  ASSERT_TRUE(presets);
  EXPECT_EQ(json::parse(presets->body).size(), 1u);
  auto r = c.Get("/api/render?preset=specular");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  auto forged = c.Get("/api/render?preset=specular", bearer(kStaff));  // a key this server does not have
  ASSERT_TRUE(forged);
  EXPECT_EQ(forged->status, 403);
}

// Every route is registered through add_route (http/route_context.h), which hands its handler the
// viewer: a handler registered on the server directly would decide what it reveals without
// asking who asks. The registrations in the sources are counted against the routes' own file.
TEST(AccessRegistrationTest, EveryRouteIsGivenItsViewerWhereItIsRegistered) {
  const std::regex direct(R"(\b(server|svr|srv)\s*(\.|->)\s*(Get|Post|Put|Patch|Delete|Options)\s*\()");
  size_t added = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(SHADELAB_SOURCE_DIR) / "server/http")) {
    const std::string text = read_text(entry.path());
    if (entry.path().filename() != "route_context.cpp") {
      EXPECT_FALSE(std::regex_search(text, direct)) << entry.path() << " registers a route without add_route";
    }
    for (size_t at = text.find("add_route(server"); at != std::string::npos; at = text.find("add_route(server", at + 1)) ++added;
  }
  EXPECT_GE(added, 19u) << "the routes of the OpenAPI document, the health checks and the metrics";
}

}  // namespace
}  // namespace shadelab::testkit
