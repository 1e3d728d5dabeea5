// prairielearn/: the external grader as PrairieLearn runs it: a job folder laid out as PrairieLearn
// lays out /grade (student/, data/data.json, serverFilesCourse/), the image's entrypoint script
// with the real shadelab binary and its render workers, and results/results.json read back.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <regex>
#include <set>

#include <nlohmann/json.hpp>

#include "core/base64.h"
#include "support/files.h"
#include "support/hand_in.h"
#include "support/prairielearn_results.h"
#include "support/run_command.h"
#include "support/test_support.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const fs::path kSource = SHADELAB_SOURCE_DIR;

class PrairieLearnTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("shadelab_prairielearn_" + std::to_string(::getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    job_ = root_ / "grade";
    fs::create_directories(job_ / "student");
    data({{"params", json::object()}, {"submitted_answers", json::object()}});
  }
  void TearDown() override { fs::remove_all(root_); }

  void data(const json& d) const { shadelab::testkit::write_file_at(job_ / "data/data.json", d.dump()); }
  void params(const json& shadelab) const { data({{"params", {{"shadelab", shadelab}}}}); }

  // The entrypoint as the image runs it, on this job; the references in one store for the suite,
  // as the image's warmed store serves every student. The time limit is a test's own (`env` may
  // set another): the default 30 s is a grader host's, and a loaded test machine may grade the
  // suite's first, cold hand-in slower than that.
  json grade(const std::string& env = "") const {
    const fs::path store = fs::temp_directory_path() / "shadelab_prairielearn_test_references";
    const auto r = shadelab::testkit::run_command("SHADELAB_TIME_LIMIT_S=600 " + env + " PRAIRIELEARN_JOB='" + job_.string() + "' SHADELAB_BIN='" + SHADELAB_CLI +
                                                  "' SHADELAB_REFERENCE_STORE='" + store.string() + "' bash '" +
                                                  (kSource / "prairielearn/entrypoint").string() + "'");
    EXPECT_EQ(r.status, 0) << r.output;
    const std::string text = shadelab::testkit::read_text(job_ / "results/results.json");
    json results = json::parse(text, nullptr, false);
    EXPECT_FALSE(results.is_discarded()) << text << r.output;
    EXPECT_LT(text.size(), 1000u * 1000u) << "PrairieLearn keeps a results file to 1 MB";
    expect_prairielearn_takes(text, r.status);
    return results;
  }

  // What PrairieLearn stores and shows is what the results file means: the job succeeded, the
  // attempt counts exactly when ShadeLab says gradable, at ShadeLab's score, every test with its
  // points and every image a data URI; an attempt not counted says why in its format errors.
  static void expect_prairielearn_takes(const std::string& text, int exit_status) {
    const json results = json::parse(text, nullptr, false);
    const auto pl = shadelab::testkit::read_as_prairielearn(text, exit_status);
    ASSERT_TRUE(pl.job_succeeded) << pl.job_message;
    EXPECT_EQ(pl.gradable, results.value("gradable", true)) << pl.invalid;
    if (pl.gradable) {
      EXPECT_DOUBLE_EQ(pl.score, results["score"].get<double>());
    } else {
      EXPECT_FALSE(pl.format_errors.empty()) << "an attempt not counted says why";
    }
    EXPECT_FALSE(pl.tests_missing_points) << "PrairieLearn would hide every test's points";
    EXPECT_EQ(pl.image_problems, std::vector<std::string>{});
  }

  // Gradescope's results for the same hand-in, its outputs in plain text (no heat maps embedded).
  json gradescope(const fs::path& submission) const {
    const fs::path out = root_ / "gradescope.json";
    const auto r = shadelab::testkit::run_shadelab("autograde '" + submission.string() + "' --results '" + out.string() +
                                                   "' --cache-dir '" + (fs::temp_directory_path() / "shadelab_prairielearn_test_references").string() + "'");
    EXPECT_EQ(r.status, 0) << r.output;
    return json::parse(shadelab::testkit::read_text(out), nullptr, false);
  }

  static std::map<std::string, json> by_name(const json& tests) {
    std::map<std::string, json> out;
    for (const auto& t : tests) out[t["name"]] = t;
    return out;
  }
  static std::string format_errors(const json& results) { return results.value("format_errors", json::array()).dump(); }

  fs::path root_, job_;
};

// PrairieLearn's rules for a question's info.json, re-stated (not copied) from its zod schema
// QuestionJsonSchema and ExternalGradingOptionsJsonSchema (apps/prairielearn/src/schemas/
// infoQuestion.ts at PrairieLearn/PrairieLearn 03b311d25): both objects strict (no other keys),
// the fields' types and enums, uuid's pattern, the image required. Each break as a sentence.
std::vector<std::string> question_schema_breaks(const json& info) {
  std::vector<std::string> breaks;
  const auto bad = [&](const std::string& what) { breaks.push_back(what); };
  if (!info.is_object()) return {"info.json is not an object"};
  static const std::set<std::string> question_keys = {
      "comment", "uuid", "type", "title", "topic", "tags", "authors", "clientFiles", "clientTemplates", "template", "gradingMethod",
      "singleVariant", "showCorrectAnswer", "partialCredit", "options", "externalGradingOptions", "dependencies", "workspaceOptions",
      "sharingSets", "sharePublicly", "shareSourcePublicly", "preferences"};
  for (const auto& [key, value] : info.items())
    if (!question_keys.count(key)) bad("unknown key " + key);
  static const std::regex uuid("^[0-9a-fA-F]{8}-[0-9a-fA-F]{4}-[0-9a-fA-F]{4}-[0-9a-fA-F]{4}-[0-9a-fA-F]{12}$");
  if (!info.contains("uuid") || !info["uuid"].is_string() || !std::regex_match(info["uuid"].get<std::string>(), uuid)) bad("uuid");
  static const std::set<std::string> types = {"Calculation", "MultipleChoice", "Checkbox", "File", "MultipleTrueFalse", "v3"};
  if (!info.contains("type") || !info["type"].is_string() || !types.count(info["type"])) bad("type");
  for (const char* text : {"title", "topic"})
    if (!info.contains(text) || !info[text].is_string()) bad(text);
  if (info.contains("tags") && (!info["tags"].is_array() || !std::all_of(info["tags"].begin(), info["tags"].end(), [](const json& t) { return t.is_string(); })))
    bad("tags");
  static const std::set<std::string> methods = {"Internal", "External", "Manual"};
  if (info.contains("gradingMethod") && (!info["gradingMethod"].is_string() || !methods.count(info["gradingMethod"]))) bad("gradingMethod");
  for (const char* flag : {"singleVariant", "showCorrectAnswer", "partialCredit", "sharePublicly", "shareSourcePublicly"})
    if (info.contains(flag) && !info[flag].is_boolean()) bad(flag);
  if (!info.contains("externalGradingOptions")) return breaks;
  const json& o = info["externalGradingOptions"];
  if (!o.is_object()) return breaks.push_back("externalGradingOptions"), breaks;
  static const std::set<std::string> option_keys = {"comment", "enabled", "image", "entrypoint", "serverFilesCourse", "timeout", "enableNetworking", "environment"};
  for (const auto& [key, value] : o.items())
    if (!option_keys.count(key)) bad("unknown key externalGradingOptions." + key);
  if (!o.contains("image") || !o["image"].is_string()) bad("externalGradingOptions.image");
  for (const char* flag : {"enabled", "enableNetworking"})
    if (o.contains(flag) && !o[flag].is_boolean()) bad(std::string("externalGradingOptions.") + flag);
  if (o.contains("timeout") && !o["timeout"].is_number_integer()) bad("externalGradingOptions.timeout");
  if (o.contains("serverFilesCourse") &&
      (!o["serverFilesCourse"].is_array() || !std::all_of(o["serverFilesCourse"].begin(), o["serverFilesCourse"].end(), [](const json& f) { return f.is_string(); })))
    bad("externalGradingOptions.serverFilesCourse");
  if (o.contains("environment")) {
    if (!o["environment"].is_object()) bad("externalGradingOptions.environment");
    else
      for (const auto& [name, value] : o["environment"].items())
        if (!value.is_string()) bad("externalGradingOptions.environment." + name + " is not a string");
  }
  return breaks;
}

// PrairieLearn's rules for an assessment's infoAssessment.json that the installer's homework
// touches, re-stated from AssessmentJsonSchema (apps/prairielearn/src/schemas/infoAssessment.ts at
// PrairieLearn/PrairieLearn 035d75a6c): the object strict, uuid, type Homework or Exam, title, set
// and number strings; each zone's questions at least one, each with an id and points at or above 0.
std::vector<std::string> assessment_schema_breaks(const json& a) {
  std::vector<std::string> breaks;
  static const std::set<std::string> keys = {
      "comment", "uuid", "type", "title", "set", "number", "allowIssueReporting", "multipleInstance", "shuffleQuestions", "allowAccess",
      "accessControl", "text", "maxPoints", "maxBonusPoints", "allowPersonalNotes", "autoClose", "zones", "constantQuestionValue",
      "allowRealTimeGrading", "requireHonorCode", "honorCode", "showQuestionTitles", "groupWork", "groupMaxSize", "groupMinSize",
      "groupRoles", "canSubmit", "canView", "studentGroupCreate", "studentGroupChooseName", "studentGroupJoin", "studentGroupLeave",
      "groups", "advanceScorePerc", "gradeRateMinutes", "module", "shareSourcePublicly", "tools"};
  if (!a.is_object()) return {"not an object"};
  for (const auto& [key, value] : a.items())
    if (!keys.count(key)) breaks.push_back("unknown key " + key);
  static const std::regex guid("^[0-9a-fA-F]{8}-[0-9a-fA-F]{4}-[0-9a-fA-F]{4}-[0-9a-fA-F]{4}-[0-9a-fA-F]{12}$");
  if (!a.contains("uuid") || !a["uuid"].is_string() || !std::regex_match(a["uuid"].get<std::string>(), guid)) breaks.push_back("uuid");
  if (!a.contains("type") || (a["type"] != "Homework" && a["type"] != "Exam")) breaks.push_back("type");
  for (const char* text : {"title", "set", "number"})
    if (!a.contains(text) || !a[text].is_string()) breaks.push_back(text);
  for (const auto& zone : a.value("zones", json::array())) {
    if (!zone.contains("questions") || !zone["questions"].is_array() || zone["questions"].empty()) breaks.push_back("a zone without questions");
    for (const auto& q : zone.value("questions", json::array())) {
      if (!q.contains("id") || !q["id"].is_string()) breaks.push_back("a question without an id");
      for (const char* points : {"points", "autoPoints", "manualPoints", "maxPoints", "maxAutoPoints"})
        if (q.contains(points) && (!q[points].is_number() || q[points].get<double>() < 0)) breaks.push_back(std::string("a question's ") + points);
      if (!q.contains("points") && !q.contains("autoPoints") && !q.contains("manualPoints")) breaks.push_back("a question without points");
    }
  }
  return breaks;
}

// pl-file-upload's size rule, re-stated from its pl-file-upload.js (PrairieLearn/PrairieLearn
// 00e1b301c): one element takes files while their combined size is at most 5 MB (5 x 1024 x 1024
// bytes), a file replacing one of its own name not counted twice.
constexpr double kPlFileUploadMaxBytes = 5.0 * 1024 * 1024;

// Whether a question's upload element takes a file by its name: its file names (either case) or its
// patterns (`*` for any run), as the element's attributes in question.html list them.
bool upload_takes(const std::string& html, const std::string& file) {
  const auto list = [&](const std::string& attribute) {
    std::vector<std::string> items;
    const size_t at = html.find(" " + attribute + "=\"");
    if (at == std::string::npos) return items;
    const size_t start = at + attribute.size() + 3, end = html.find('"', start);
    std::string rest = html.substr(start, end - start);
    for (size_t from = 0; from <= rest.size();) {
      const size_t comma = std::min(rest.find(',', from), rest.size());
      std::string item = rest.substr(from, comma - from);
      item.erase(0, item.find_first_not_of(' '));
      if (!item.empty()) items.push_back(item);
      from = comma + 1;
    }
    return items;
  };
  const auto lower = [](std::string t) { std::transform(t.begin(), t.end(), t.begin(), ::tolower); return t; };
  for (const char* names : {"file-names", "optional-file-names"})
    for (const auto& n : list(names))
      if (lower(n) == lower(file)) return true;
  for (const char* patterns : {"file-patterns", "optional-file-patterns"})
    for (const auto& p : list(patterns)) {
      std::string re;
      for (const char c : p) re += c == '*' ? std::string(".*") : std::isalnum(static_cast<unsigned char>(c)) ? std::string(1, c) : "\\" + std::string(1, c);
      if (std::regex_match(lower(file), std::regex(lower(re)))) return true;
    }
  return false;
}

}  // namespace

// The schema check itself finds what PrairieLearn's sync would refuse.
TEST(PrairieLearnSchemaTest, TheQuestionRulesCatchWhatPrairieLearnsSyncRefuses) {
  const json good = json::parse(R"({"uuid": "6f1c2d0e-8a4b-4e57-9d1a-3b2c5e7f9a10", "type": "v3", "title": "t", "topic": "Shading",
    "gradingMethod": "External", "externalGradingOptions": {"image": "a/b", "timeout": 45, "environment": {"X": "1"}}})");
  EXPECT_TRUE(question_schema_breaks(good).empty());
  const auto breaks_with = [&](const std::string& pointer, const json& value) {
    json changed = good;
    changed[json::json_pointer(pointer)] = value;
    return question_schema_breaks(changed).size();
  };
  EXPECT_EQ(breaks_with("/externalGradingOptions/timeout", "45"), 1u);
  EXPECT_EQ(breaks_with("/externalGradingOptions/environment/X", 1), 1u);
  EXPECT_EQ(breaks_with("/externalGradingOptions/memory", 2048), 1u);
  EXPECT_EQ(breaks_with("/uuid", "not-a-uuid"), 1u);
  EXPECT_EQ(breaks_with("/type", "Freeform"), 1u);
  EXPECT_EQ(breaks_with("/shadelab", json::object()), 1u);
  json no_image = good;
  no_image["externalGradingOptions"].erase("image");
  EXPECT_EQ(question_schema_breaks(no_image).size(), 1u);
}

// The re-coded parser refuses what PrairieLearn refuses, so the checks above can fail.
TEST(PrairieLearnResultsTest, TheParserTakesWhatPrairieLearnTakesAndNothingElse) {
  using shadelab::testkit::read_as_prairielearn;
  const auto pl = [](const json& results, int status = 0) { return read_as_prairielearn(results.dump(), status); };
  const json good = {{"gradable", true}, {"score", 0.5}, {"tests", {{{"name", "a"}, {"points", 1}, {"max_points", 2}}}}};
  EXPECT_TRUE(pl(good).gradable);
  EXPECT_DOUBLE_EQ(pl(good).score, 0.5);
  EXPECT_FALSE(pl(good, 1).job_succeeded) << "a container that exits non-zero is a failed job";
  EXPECT_FALSE(read_as_prairielearn(std::string(1024 * 1024 + 1, ' ')).job_succeeded) << "over 1 MiB";
  EXPECT_FALSE(read_as_prairielearn("{\"score\": 1").job_succeeded) << "not JSON";
  EXPECT_FALSE(read_as_prairielearn("null").job_succeeded);
  const auto with = [&](const char* key, const json& value) {
    json changed = good;
    changed[key] = value;
    return pl(changed);
  };
  EXPECT_EQ(with("score", 1.2).invalid, "score is out of range.");
  EXPECT_EQ(with("score", "1").invalid, "score is not a number.");
  EXPECT_EQ(with("score", nullptr).invalid, "score is not a number.");
  json no_score = good;
  no_score.erase("score");
  EXPECT_EQ(pl(no_score).invalid, "score was not provided.");
  EXPECT_FALSE(with("gradable", false).gradable);
  EXPECT_FALSE(with("gradable", 0).gradable) << "JavaScript's !!0";
  EXPECT_TRUE(with("gradable", nullptr).gradable) << "?? true";
  EXPECT_DOUBLE_EQ(with("succeeded", false).score, 0);
  EXPECT_EQ(with("format_errors", "one").format_errors, std::vector<std::string>{"one"});
  json missing = good;
  missing["tests"][0].erase("max_points");
  EXPECT_TRUE(pl(missing).tests_missing_points);
  EXPECT_EQ(with("images", json::array({{{"url", "https://grader.internal/x.png"}}})).image_problems.size(), 1u);
  EXPECT_TRUE(with("images", json::array({{{"label", "x"}, {"url", "data:image/png;base64,AA=="}}})).image_problems.empty());
}

// The real student's hand-in (their HW2 folder's files), uploaded as PrairieLearn's file upload
// keeps them, without folders; the specular code wrong: every Gradescope test is a PrairieLearn
// test with the same words and points, the failed one with its heat map, and the student's grids
// beside them.
TEST_F(PrairieLearnTest, AHandInIsGradedTestForTestAsOnGradescope) {
  shadelab::testkit::write_hand_in(root_ / "HW2-folder", "specular", "diffuse");
  for (const auto& f : fs::recursive_directory_iterator(root_ / "HW2-folder"))
    if (f.is_regular_file()) fs::copy_file(f.path(), job_ / "student" / f.path().filename());
  const json results = grade();
  ASSERT_TRUE(results.value("gradable", false)) << results.dump(2);
  const json expected = gradescope(job_ / "student");
  const auto tests = by_name(results["tests"]);
  ASSERT_EQ(tests.size(), expected["tests"].size()) << results.dump(2);
  double points = 0, max_points = 0;
  for (const auto& g : expected["tests"]) {
    ASSERT_TRUE(tests.contains(g["name"])) << g["name"] << " is not among PrairieLearn's tests";
    const json& t = tests.at(g["name"]);
    EXPECT_EQ(t["output"], g["output"]) << "the same words as on Gradescope";
    EXPECT_DOUBLE_EQ(t["points"].get<double>(), g["score"].get<double>()) << g["name"];
    EXPECT_DOUBLE_EQ(t["max_points"].get<double>(), g["max_score"].get<double>()) << g["name"];
    EXPECT_EQ(t["message"].get<std::string>(), t["output"].get<std::string>().substr(0, t["output"].get<std::string>().find('\n')));
    points += g["score"].get<double>();
    max_points += g["max_score"].get<double>();
  }
  EXPECT_NEAR(results["score"].get<double>(), points / max_points, 1e-6);
  EXPECT_LT(results["score"].get<double>(), 1.0);
  // The code test fails with the specular highlight missing, and shows where.
  const std::string code_name = expected["tests"][5]["name"];
  const json& code = tests.at(code_name);
  ASSERT_EQ(code["points"], 0) << code.dump(2);
  EXPECT_NE(code["output"].get<std::string>().find("specular"), std::string::npos) << code["output"];
  ASSERT_TRUE(code.contains("images")) << code.dump(2);
  EXPECT_TRUE(code["images"][0]["url"].get<std::string>().starts_with("data:image/png;base64,"));
  // Each deliverable's saved frames as a grid the student sees.
  ASSERT_EQ(results["images"].size(), 3u) << results["output"];
  for (const auto& image : results["images"]) {
    EXPECT_NE(image["label"].get<std::string>().find("the frames you saved"), std::string::npos) << image["label"];
    EXPECT_TRUE(image["url"].get<std::string>().starts_with("data:image/png;base64,"));
  }
  EXPECT_EQ(results["output"].get<std::string>().find("Not shown"), std::string::npos) << "everything fits in 1 MB: " << results["output"];
  // The Blender half found without its images/ folder, and judged.
  const json& camera = tests.at("Dolly zoom: 25 mm (images/camera_25.png)");
  EXPECT_NE(camera["output"].get<std::string>().find("matches the handout's camera"), std::string::npos) << camera["output"];
}

// A checkpoint question: the student edits the two shaders in the page's editors and submits code
// alone. Graded as code (its code and hidden-light tests), with a grid of what the code draws.
TEST_F(PrairieLearnTest, ACheckpointQuestionGradesTheCodeAlone) {
  params({{"checkpoint", "specular"}});
  shadelab::testkit::write_file_at(job_ / "student/phong_vert.js", shadelab::testkit::preset_module("specular", "vert"));
  shadelab::testkit::write_file_at(job_ / "student/phong_frag.js", shadelab::testkit::preset_module("specular", "frag"));
  const json results = grade();
  ASSERT_TRUE(results.value("gradable", false)) << results.dump(2);
  EXPECT_EQ(results["score"], 1.0) << results.dump(2);
  ASSERT_EQ(results["tests"].size(), 2u) << results.dump(2);
  EXPECT_NE(results["tests"][0]["name"].get<std::string>().find(": code (phong_vert.js, phong_frag.js)"), std::string::npos);
  EXPECT_NE(results["tests"][1]["name"].get<std::string>().find("code under a hidden light"), std::string::npos);
  ASSERT_EQ(results["images"].size(), 1u);
  EXPECT_NE(results["images"][0]["label"].get<std::string>().find("what your code draws"), std::string::npos);
}

// A broken shader is the student's: gradable, 0, with the compiler's words at their line.
TEST_F(PrairieLearnTest, AShaderThatDoesNotCompileIsAZeroWithItsReason) {
  params({{"checkpoint", "specular"}});
  std::string broken = shadelab::testkit::preset_module("specular", "frag");
  const size_t at = broken.find("void main");
  broken.replace(at, 4, "vod");
  const long line = 1 + std::count(broken.begin(), broken.begin() + static_cast<long>(at), '\n');
  shadelab::testkit::write_file_at(job_ / "student/phong_vert.js", shadelab::testkit::preset_module("specular", "vert"));
  shadelab::testkit::write_file_at(job_ / "student/phong_frag.js", broken);
  const json results = grade();
  ASSERT_TRUE(results.value("gradable", false)) << results.dump(2);
  EXPECT_EQ(results["score"], 0) << results.dump(2);
  EXPECT_NE(results["tests"][0]["output"].get<std::string>().find("compile error at phong_frag.js line " + std::to_string(line) + ":"), std::string::npos)
      << results["tests"][0]["output"];
  EXPECT_EQ(results["images"].size(), 0u) << "a pair that does not compile draws nothing";
}

// A file name with an escape code is shown, not obeyed: PrairieLearn's ansi2html would style the
// results' output with it (docs/reliability.md, "The attacker").
TEST_F(PrairieLearnTest, AFileNamesEscapeCodesAreShownNotObeyed) {
  params({{"checkpoint", "specular"}});
  std::string broken = shadelab::testkit::preset_module("specular", "frag");
  broken.replace(broken.find("void main"), 4, "vod");
  shadelab::testkit::write_file_at(job_ / "student/phong_vert.js", shadelab::testkit::preset_module("specular", "vert"));
  shadelab::testkit::write_file_at(job_ / "student/phong\x1b[8m_frag.js", broken);
  const json results = grade();
  const std::string text = results.dump();
  EXPECT_EQ(text.find("\\u001b"), std::string::npos) << "an escape code reached PrairieLearn's results";
  EXPECT_NE(text.find("phong\\\\x1B[8m_frag.js"), std::string::npos) << results.dump(2);
}

// Only a malformed job is not gradable, and each says why in words for PrairieLearn's format errors.
TEST_F(PrairieLearnTest, AMalformedJobIsNotGradableAndSaysWhy) {
  shadelab::testkit::write_file_at(job_ / "student/phong_vert.js", shadelab::testkit::preset_module("specular", "vert"));
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{not json", "not a JSON object"},
      {R"({"params": {"shadelab": {"checkpoint": "shiny"}}})", "shiny"},
      {R"({"params": {"shadelab": {"checkpoint": "diffuse"}}})", "graded by its saved frames alone"},
      {R"({"params": {"shadelab": {"course": "../../etc/course.json"}}})", "a path inside the grading job"},
      {R"({"params": {"shadelab": {"grade": "all"}}})", "params.shadelab"},
  };
  for (const auto& [text, words] : cases) {
    shadelab::testkit::write_file_at(job_ / "data/data.json", text);
    const json results = grade();
    EXPECT_EQ(results["gradable"], false) << text << ": " << results.dump(2);
    EXPECT_NE(format_errors(results).find(words), std::string::npos) << text << ": " << format_errors(results);
  }
  fs::remove(job_ / "data/data.json");
  EXPECT_NE(format_errors(grade()).find("no data/data.json"), std::string::npos);
  data({{"params", json::object()}});
  fs::remove_all(job_ / "student");
  fs::create_directories(job_ / "student");
  EXPECT_NE(format_errors(grade()).find("no files were submitted"), std::string::npos);
}

// The grader cannot run here (EGL finds no driver): a results file that says so, not gradable, so
// the student is not charged an attempt.
TEST_F(PrairieLearnTest, AGraderWithoutGLWritesWhy) {
  shadelab::testkit::write_hand_in(job_ / "student");
  const json results = grade("__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json");
  EXPECT_EQ(results["gradable"], false) << results.dump(2);
  EXPECT_NE(format_errors(results).find("not a problem with your submission"), std::string::npos) << format_errors(results);
  EXPECT_NE(format_errors(results).find("EGL"), std::string::npos) << format_errors(results);
}

// A time limit too short to grade in: the results are written before it, name what was not
// finished, and do not count the attempt.
TEST_F(PrairieLearnTest, AGradeCutShortByTheTimeLimitSaysWhatItDidNotFinish) {
  params({{"checkpoint", "specular"}});
  shadelab::testkit::write_file_at(job_ / "student/phong_vert.js", shadelab::testkit::preset_module("specular", "vert"));
  shadelab::testkit::write_file_at(job_ / "student/phong_frag.js", shadelab::testkit::preset_module("specular", "frag"));
  const json results = grade("SHADELAB_TIME_LIMIT_S=2");  // less than the margin kept for writing: nothing can finish
  EXPECT_EQ(results["gradable"], false) << results.dump(2);
  EXPECT_NE(format_errors(results).find("ran out of the time"), std::string::npos) << format_errors(results);
  EXPECT_NE(format_errors(results).find("Not finished: Specular"), std::string::npos) << format_errors(results);
}

// The grader is missing from the image: the entrypoint still writes a results file that says so.
TEST_F(PrairieLearnTest, AMissingGraderStillWritesResults) {
  const auto r = shadelab::testkit::run_command("PRAIRIELEARN_JOB='" + job_.string() + "' SHADELAB_BIN=/nonexistent/shadelab bash '" +
                                                (kSource / "prairielearn/entrypoint").string() + "'");
  EXPECT_EQ(r.status, 0) << r.output;
  const std::string text = shadelab::testkit::read_text(job_ / "results/results.json");
  const json results = json::parse(text, nullptr, false);
  EXPECT_EQ(results["gradable"], false) << results.dump(2);
  EXPECT_NE(format_errors(results).find("not installed"), std::string::npos) << format_errors(results);
  expect_prairielearn_takes(text, r.status);
}

// The two question templates, installed into a PrairieLearn course as a TA would: each a question
// PrairieLearn can load (a fresh uuid, external grading on the image, its timeout passed to the
// grader), the checkpoint question's editors on the public starter and its live canvas with every
// module it imports; and nothing of a reference anywhere in the course's files.
TEST_F(PrairieLearnTest, TheQuestionTemplatesInstallWithoutAReference) {
  const fs::path course = root_ / "pl-course";
  const auto r = shadelab::testkit::run_command("SHADELAB_BIN='" + std::string(SHADELAB_CLI) + "' python3 '" +
                                                (kSource / "prairielearn/install_questions.py").string() + "' '" + course.string() +
                                                "' --image registry.example.edu/cs148/shadelab-grader");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* name : {"shadelab-hw2-frames-and-code", "shadelab-hw2-blender", "shadelab-hw2-specular"}) {
    const fs::path q = course / "questions" / name;
    const json info = json::parse(shadelab::testkit::read_text(q / "info.json"), nullptr, false);
    ASSERT_FALSE(info.is_discarded()) << name;
    const json template_info = json::parse(shadelab::testkit::read_text(kSource / "prairielearn/questions" /
                                                                        (std::string(name) == "shadelab-hw2-specular" ? "checkpoint" : "hand-in") / "info.json"));
    EXPECT_EQ(info["uuid"].get<std::string>().size(), 36u);
    EXPECT_NE(info["uuid"], template_info["uuid"]) << "each installed question has its own uuid";
    EXPECT_EQ(info["gradingMethod"], "External");
    const json& options = info["externalGradingOptions"];
    EXPECT_EQ(options["image"], "registry.example.edu/cs148/shadelab-grader");
    EXPECT_EQ(options["environment"]["SHADELAB_TIME_LIMIT_S"], std::to_string(options["timeout"].get<int>())) << "the grader knows the timeout";
    EXPECT_TRUE(fs::exists(q / "question.html"));
    EXPECT_EQ(question_schema_breaks(info), std::vector<std::string>{}) << name;
  }
  const fs::path checkpoint = course / "questions/shadelab-hw2-specular";
  EXPECT_NE(shadelab::testkit::read_text(checkpoint / "server.py").find(R"(SHADELAB = {"checkpoint": "specular"})"), std::string::npos);
  EXPECT_EQ(shadelab::testkit::read_text(checkpoint / "phong_vert.js"), shadelab::testkit::read_text(kSource / "shaders/starter_vert.js"));
  EXPECT_EQ(shadelab::testkit::read_text(checkpoint / "phong_frag.js"), shadelab::testkit::read_text(kSource / "shaders/starter_frag.js"));
  const std::string live = shadelab::testkit::read_text(checkpoint / "clientFilesQuestion/live.js");
  for (size_t at = live.find("from \"./"); at != std::string::npos; at = live.find("from \"./", at + 1)) {
    const std::string module = live.substr(at + 8, live.find('"', at + 8) - at - 8);
    EXPECT_TRUE(fs::exists(checkpoint / "clientFilesQuestion" / module)) << module << " is imported by live.js";
  }
  EXPECT_EQ(shadelab::testkit::read_text(checkpoint / "clientFilesQuestion/bunny.obj"), shadelab::testkit::read_text(kSource / "assets/bunny.obj"));
  const json facts = json::parse(shadelab::testkit::read_text(checkpoint / "clientFilesQuestion/course.json"));
  EXPECT_EQ(facts["viewer"]["role"], "student");
  for (const auto& preset : facts["presets"]) EXPECT_TRUE(preset["public"].get<bool>()) << preset["name"];
  // No reference's shader reaches the course's files (the references' main bodies, byte for byte).
  for (const char* reference : {"normals", "diffuse", "specular"})
    for (const char* stage : {"vert", "frag"}) {
      const std::string source = shadelab::testkit::preset_module(reference, stage);
      const std::string body = source.substr(source.find("void main"));
      for (const auto& f : fs::recursive_directory_iterator(course))
        if (f.is_regular_file()) {
          EXPECT_EQ(shadelab::testkit::read_text(f.path()).find(body), std::string::npos) << reference << " " << stage << " in " << f.path();
        }
    }
}

// `install_questions.py --course` with a profile as `course import` writes it, in a TA's working
// folder (the profile names its files `../HW2/...`, and submissions sit beside it): only the
// files the profile names are installed, the profile rewritten to name them where they land, and
// a checkpoint graded by it once the TA's folder is gone: the imported exponent (10), not the
// built-in course's (6).
TEST_F(PrairieLearnTest, AnImportedCourseInstallsOnlyItsFilesAndGradesByThem) {
  namespace tk = shadelab::testkit;
  const fs::path ta = root_ / "ta", hw = ta / "HW2";
  tk::write_file_at(hw / "index.html", "<canvas id=\"glcanvas\" width=\"512\" height=\"512\"></canvas>\n");
  tk::write_file_at(hw / "src/hw2.js", "const IMAGE_PREFIX = \"normals\";\nconst OBJ_FILE = \"assets/bunny.obj\";\n");
  tk::write_file_at(hw / "src/shaders/starter_vert.js", tk::read_text(kSource / "shaders/starter_vert.js"));
  tk::write_file_at(hw / "src/shaders/starter_frag.js", tk::read_text(kSource / "shaders/starter_frag.js"));
  tk::write_file_at(hw / "src/shaders/phong_vert.js", tk::preset_module("specular", "vert"));
  std::string phong = tk::preset_module("specular", "frag");
  const std::string six = "float specularAlpha = 6.0;";
  ASSERT_NE(phong.find(six), std::string::npos);
  phong.replace(phong.find(six), six.size(), "float specularAlpha = 10.0;");
  tk::write_file_at(hw / "src/shaders/phong_frag.js", phong);
  tk::write_file_at(hw / "assets/bunny.obj", tk::read_text(kSource / "assets/bunny.obj"));
  tk::write_file_at(ta / "profiles/submissions/alice/phong_frag.js", "a student's hand-in, not the course's");
  const auto imported = tk::run_shadelab("course import '" + hw.string() + "' -o '" + (ta / "profiles/course.json").string() + "'");
  ASSERT_EQ(imported.status, 0) << imported.output;
  ASSERT_NE(tk::read_text(ta / "profiles/course.json").find("../HW2/"), std::string::npos) << "named relative to the profile";

  const fs::path course = root_ / "pl-course";
  const auto r = tk::run_command("SHADELAB_BIN='" + std::string(SHADELAB_CLI) + "' python3 '" +
                                 (kSource / "prairielearn/install_questions.py").string() + "' '" + course.string() +
                                 "' --course '" + (ta / "profiles/course.json").string() + "'");
  ASSERT_EQ(r.status, 0) << r.output;
  const fs::path installed = course / "serverFilesCourse/shadelab";
  const std::string profile = tk::read_text(installed / "course.json");
  for (const auto& f : fs::recursive_directory_iterator(installed)) {
    EXPECT_TRUE(f.is_regular_file()) << f.path() << ": no folders, the TA's submissions least of all";
    const std::string name = f.path().filename().string();
    if (name != "course.json") {
      EXPECT_NE(profile.find("\"" + name + "\""), std::string::npos) << name << " is not named by the profile";
    }
  }
  EXPECT_EQ(profile.find("\"" + ta.string()), std::string::npos) << "the installed profile names no file outside its folder";
  EXPECT_EQ(profile.find("\"../"), std::string::npos) << "the installed profile names no file outside its folder";
  for (const char* question : {"shadelab-hw2-frames-and-code", "shadelab-hw2-blender", "shadelab-hw2-specular"}) {
    const json info = json::parse(tk::read_text(course / "questions" / question / "info.json"));
    EXPECT_EQ(question_schema_breaks(info), std::vector<std::string>{}) << question;
    EXPECT_EQ(info["externalGradingOptions"]["serverFilesCourse"], json::array({"shadelab/"}));
  }
  fs::remove_all(ta);

  fs::copy(course / "serverFilesCourse", job_ / "serverFilesCourse", fs::copy_options::recursive);
  params({{"checkpoint", "specular"}, {"course", "serverFilesCourse/shadelab/course.json"}});
  tk::write_file_at(job_ / "student/phong_vert.js", tk::preset_module("specular", "vert"));
  tk::write_file_at(job_ / "student/phong_frag.js", phong);
  json results = grade();
  ASSERT_TRUE(results.value("gradable", false)) << results.dump(2);
  EXPECT_EQ(results["score"], 1.0) << results.dump(2);
  tk::write_file_at(job_ / "student/phong_frag.js", tk::preset_module("specular", "frag"));
  results = grade();
  ASSERT_TRUE(results.value("gradable", false)) << results.dump(2);
  EXPECT_LT(results["score"].get<double>(), 1.0) << "the built-in exponent fails the imported course";
}

// The checkpoint question says what its deliverable asks, in the course's words: the normals
// question names no exponent and no light (its formula has neither), the specular one both.
TEST_F(PrairieLearnTest, ACheckpointQuestionSaysOnlyWhatItsDeliverableAsks) {
  const auto install = [&](const std::string& checkpoint) {
    const fs::path course = root_ / ("pl-" + checkpoint);
    const auto r = shadelab::testkit::run_command("SHADELAB_BIN='" + std::string(SHADELAB_CLI) + "' python3 '" +
                                                  (kSource / "prairielearn/install_questions.py").string() + "' '" + course.string() +
                                                  "' --checkpoint " + checkpoint);
    EXPECT_EQ(r.status, 0) << r.output;
    return shadelab::testkit::read_text(course / "questions" / ("shadelab-hw2-" + checkpoint) / "question.html");
  };
  const std::string normals = install("normals"), specular = install("specular");
  EXPECT_NE(normals.find("the normals deliverable, the normal colour computed in the vertex shader."), std::string::npos) << normals;
  EXPECT_EQ(normals.find("specularAlpha"), std::string::npos) << normals;
  EXPECT_EQ(normals.find("light"), std::string::npos) << normals;
  EXPECT_EQ(normals.find("Normals:"), std::string::npos) << "the title is the page's heading, not repeated" << normals;
  EXPECT_NE(specular.find("<code>specularAlpha = 6.0</code>"), std::string::npos) << specular;
  EXPECT_NE(specular.find("under a hidden one"), std::string::npos) << specular;
}

// The hand-in in two parts, as two questions take it (PrairieLearn's upload holds 5 MB; a real
// hand-in is 8.6 MB): the deliverables' saved frames and code, and the Blender half's images. Each
// part's tests are the whole hand-in's tests of that part, word for word and point for point;
// neither reports the other's files missing; together they are the Gradescope total.
TEST_F(PrairieLearnTest, AHandInInPartsGradesEachPartAsTheWholeDoesAndNothingElse) {
  shadelab::testkit::write_hand_in(root_ / "HW2-folder", "specular", "diffuse");
  std::vector<fs::path> all;
  for (const auto& f : fs::recursive_directory_iterator(root_ / "HW2-folder"))
    if (f.is_regular_file()) all.push_back(f.path());
  fs::create_directories(root_ / "flat");  // as PrairieLearn's upload keeps them, and as the parts hold them
  for (const auto& f : all) fs::copy_file(f, root_ / "flat" / f.filename());
  const json expected = gradescope(root_ / "flat");
  const auto is_image = [](const fs::path& f) {
    const std::string name = f.filename().string();
    return name.starts_with("camera_") || name.starts_with("eevee");
  };
  std::map<std::string, json> graded;
  for (const char* part : {"deliverables", "images"}) {
    fs::remove_all(job_ / "student");
    fs::create_directories(job_ / "student");
    for (const auto& f : all)
      if (is_image(f) == (std::string(part) == "images")) fs::copy_file(f, job_ / "student" / f.filename());
    params({{"part", part}});
    graded[part] = grade();
    ASSERT_TRUE(graded[part].value("gradable", false)) << part << graded[part].dump(2);
  }
  const auto deliverables = by_name(graded["deliverables"]["tests"]), images = by_name(graded["images"]["tests"]);
  EXPECT_FALSE(deliverables.empty());
  EXPECT_FALSE(images.empty());
  double max_points = 0;
  for (const auto& g : expected["tests"]) {
    const std::string name = g["name"];
    const bool image = name.find("camera_") != std::string::npos || name.find("eevee") != std::string::npos;
    const auto& mine = image ? images : deliverables;
    const auto& other = image ? deliverables : images;
    ASSERT_TRUE(mine.contains(name)) << name << " is not in its part";
    EXPECT_FALSE(other.contains(name)) << name << " is in the other part too";
    EXPECT_EQ(mine.at(name)["output"], g["output"]) << name;
    EXPECT_DOUBLE_EQ(mine.at(name)["points"].get<double>(), g["score"].get<double>()) << name;
    max_points += g["max_score"].get<double>();
  }
  EXPECT_EQ(deliverables.size() + images.size(), expected["tests"].size()) << "no test of its own in either part";
  double parts_max = 0;
  for (const auto& [part, results] : graded)
    for (const auto& t : results["tests"]) parts_max += t["max_points"].get<double>();
  EXPECT_DOUBLE_EQ(parts_max, max_points) << "the parts add up to the Gradescope total";
}

// A part is one of the two; a question names a checkpoint or a part, not both.
TEST_F(PrairieLearnTest, AQuestionsPartIsOneOfTheTwoAndNotBesideACheckpoint) {
  shadelab::testkit::write_file_at(job_ / "student/phong_frag.js", shadelab::testkit::preset_module("specular", "frag"));
  params({{"part", "notebook"}});
  json results = grade();
  EXPECT_FALSE(results.value("gradable", true));
  EXPECT_NE(format_errors(results).find("deliverables (the saved frames and code) or images"), std::string::npos) << results.dump(2);
  params({{"part", "images"}, {"checkpoint", "specular"}});
  results = grade();
  EXPECT_FALSE(results.value("gradable", true));
  EXPECT_NE(format_errors(results).find("both a checkpoint and a part"), std::string::npos) << results.dump(2);
}

// A real summer-2022 hand-in, by its files' sizes (27 frames saved from the page, 3.09 MB; three
// camera renders and the Eevee render, 4.46 MB; the notebook, 1.04 MB; four shaders, 3 KB),
// through the installed questions' upload elements and pl-file-upload's size rule: the single
// question cannot take it; the parts take every file once, each within 5 MB; the homework's points
// are the Gradescope total and pass PrairieLearn's assessment rules.
TEST_F(PrairieLearnTest, ARealHandInGoesInWholeThroughTheQuestionsPerPart) {
  namespace tk = shadelab::testkit;
  std::map<std::string, double> hand_in;
  for (const char* stem : {"starter", "phong"})
    for (const char* stage : {"vert", "frag"}) hand_in[std::string(stem) + "_" + stage + ".js"] = 750;
  for (const char* prefix : {"normals", "diffuse", "specular"})
    for (int k = 0; k < 9; ++k) hand_in["hw2_" + std::string(prefix) + "_" + std::to_string(k) + ".png"] = 3.09e6 / 27;
  for (const char* render : {"camera_25.png", "camera_50.png", "camera_100.png", "eevee0001.png"}) hand_in[render] = 4.46e6 / 4;
  hand_in["HW2.ipynb"] = 1.04e6;
  double total = 0;
  for (const auto& [name, bytes] : hand_in) total += bytes;
  EXPECT_GT(total, kPlFileUploadMaxBytes) << "the whole hand-in does not fit one upload";

  const fs::path course = root_ / "pl-course";
  const auto r = tk::run_command("SHADELAB_BIN='" + std::string(SHADELAB_CLI) + "' python3 '" +
                                 (kSource / "prairielearn/install_questions.py").string() + "' '" + course.string() + "' --course-instance Fa26");
  ASSERT_EQ(r.status, 0) << r.output;
  const json assessment = json::parse(tk::read_text(course / "courseInstances/Fa26/assessments/shadelab-hw2/infoAssessment.json"));
  EXPECT_EQ(assessment_schema_breaks(assessment), std::vector<std::string>{}) << assessment.dump(2);
  std::map<std::string, double> in_part;
  double points = 0;
  for (const auto& q : assessment["zones"][0]["questions"]) {
    const std::string id = q["id"];
    const json info = json::parse(tk::read_text(course / "questions" / id / "info.json"));
    EXPECT_EQ(question_schema_breaks(info), std::vector<std::string>{}) << id;
    points += q.value("autoPoints", 0.0) + q.value("manualPoints", 0.0);
    const std::string html = tk::read_text(course / "questions" / id / "question.html");
    for (const auto& [name, bytes] : hand_in)
      if (upload_takes(html, name)) {
        EXPECT_FALSE(in_part.count(name)) << name << " is taken by two questions";
        in_part[name] = bytes;
        double& sum = in_part["total of " + id];
        sum += bytes;
      }
  }
  for (const auto& [name, bytes] : hand_in) EXPECT_TRUE(in_part.count(name)) << name << " has no question to go in";
  for (const auto& [name, bytes] : in_part)
    if (name.starts_with("total of ")) {
      EXPECT_LE(bytes, kPlFileUploadMaxBytes) << name << ": " << bytes << " bytes";
    }
  // The homework is worth what Gradescope's autograder gives for the whole hand-in.
  const auto show = tk::run_shadelab("course show");
  const json facts = json::parse(show.output.substr(show.output.find('{')));
  double gradescope = 0;
  for (const auto& k : facts["checkpoints"]) gradescope += k["points"].get<double>();
  for (const auto& image : facts["notebook"]["images"]) gradescope += image.value("points", 0.0);
  EXPECT_DOUBLE_EQ(points, gradescope);
  // The assessment rules catch what a sync refuses.
  json broken = assessment;
  broken["zones"][0]["questions"][0]["autoPoints"] = -1;
  broken["type"] = "Quiz";
  EXPECT_EQ(assessment_schema_breaks(broken).size(), 2u);
}

// The same hand-in as real files at the real dimensions, every one made by ShadeLab: the 27 frames
// saved from the page (512 x 512 PNGs), the three dolly-zoom cameras and the Eevee render at the
// 1920 x 1080 students hand in (`shadelab scene` on the course's scenes), and the notebook as run,
// its cells showing the three grids and the four renders. Each question's files pass
// pl-file-upload's rule by their own bytes, and each graded part comes back gradable, within 1 MiB,
// read by PrairieLearn's parser. ShadeLab's renders are flat-shaded and compress better than
// Blender's (about 0.1-0.4 MB against 1.1 MB a render), so the byte counts of the real hand-in
// above remain the binding case; this one proves the files themselves go through.
TEST_F(PrairieLearnTest, ARealHandInsFilesGoInByTheirOwnBytesAndAreGraded) {
  namespace tk = shadelab::testkit;
  const fs::path hand_in = root_ / "hand-in", work = root_ / "work";
  for (const char* deliverable : {"normals", "diffuse", "specular"}) {
    tk::save_page_frames(hand_in, deliverable, deliverable, "--grid '" + (work / (std::string(deliverable) + "_grid.png")).string() + "'");
  }
  const std::map<std::string, std::pair<std::string, std::string>> renders = {  // file: scene, lens
      {"camera_25.png", {"dolly_25mm", ""}}, {"camera_50.png", {"dolly_50mm", ""}}, {"camera_100.png", {"dolly_100mm", ""}}, {"eevee0001.png", {"two_objects", ""}}};
  for (const auto& [file, scene] : renders) {
    json description = json::parse(tk::read_text(kSource / "assets/scenes" / (scene.first + ".json")));
    description["render"]["width"] = 1920;
    description["render"]["height"] = 1080;
    tk::write_file_at(work / (scene.first + ".json"), description.dump());
    const auto r = tk::run_shadelab("scene '" + (work / (scene.first + ".json")).string() + "' -o '" + (hand_in / file).string() + "'");
    ASSERT_EQ(r.status, 0) << r.output;
  }
  for (const char* stem : {"starter", "phong"})
    for (const char* stage : {"vert", "frag"})
      tk::write_file_at(hand_in / (std::string(stem) + "_" + stage + ".js"), tk::preset_module(std::string(stem) == "starter" ? "normals" : "specular", stage));
  json notebook = json::parse(tk::read_text(kSource / "assets/notebooks/hw2_handed_out.ipynb"));
  const auto show = [](const fs::path& png) {
    return json{{"output_type", "display_data"}, {"metadata", json::object()},
                {"data", {{"image/png", shadelab::base64_encode(tk::read_text(png))}, {"text/plain", "<IPython.core.display.Image object>"}}}};
  };
  for (auto& cell : notebook["cells"]) {
    if (cell["cell_type"] != "code") continue;
    const std::string code = cell["source"].is_array() ? cell["source"].dump() : cell["source"].get<std::string>();
    for (const char* deliverable : {"normals", "diffuse", "specular"})
      if (code.find(std::string("hw2_") + deliverable + "_*") != std::string::npos) cell["outputs"].push_back(show(work / (std::string(deliverable) + "_grid.png")));
    for (const auto& [file, scene] : renders)
      if (code.find(file.starts_with("camera_") ? "camera_*" : "eevee0001") != std::string::npos) cell["outputs"].push_back(show(hand_in / file));
  }
  tk::write_file_at(hand_in / "HW2.ipynb", notebook.dump(1));

  const fs::path course = root_ / "pl-course";
  const auto r = tk::run_command("SHADELAB_BIN='" + std::string(SHADELAB_CLI) + "' python3 '" +
                                 (kSource / "prairielearn/install_questions.py").string() + "' '" + course.string() + "' --course-instance Fa26");
  ASSERT_EQ(r.status, 0) << r.output;
  const json assessment = json::parse(tk::read_text(course / "courseInstances/Fa26/assessments/shadelab-hw2/infoAssessment.json"));
  std::set<std::string> placed;
  for (const auto& q : assessment["zones"][0]["questions"]) {
    const std::string id = q["id"];
    const std::string html = tk::read_text(course / "questions" / id / "question.html");
    fs::remove_all(job_ / "student");
    fs::create_directories(job_ / "student");
    double bytes = 0;
    for (const auto& f : fs::directory_iterator(hand_in))
      if (upload_takes(html, f.path().filename().string())) {
        EXPECT_TRUE(placed.insert(f.path().filename().string()).second) << f.path().filename() << " is taken by two questions";
        bytes += static_cast<double>(fs::file_size(f.path()));
        fs::copy_file(f.path(), job_ / "student" / f.path().filename());
      }
    EXPECT_LE(bytes, kPlFileUploadMaxBytes) << id << " takes " << bytes << " bytes";
    RecordProperty(id, std::to_string(static_cast<long>(bytes)));
    const json info = json::parse(tk::read_text(course / "questions" / id / "info.json"));
    if (info.value("gradingMethod", "") != "External") continue;  // the notebook is read by a TA
    const std::string server = tk::read_text(course / "questions" / id / "server.py");
    const size_t at = server.find("SHADELAB = ");
    ASSERT_NE(at, std::string::npos) << id << " names no params.shadelab";
    params(json::parse(server.substr(at + 11, server.find('\n', at) - at - 11)));
    const json results = grade();
    EXPECT_TRUE(results.value("gradable", false)) << id << ": " << results.dump(2).substr(0, 2000);
    EXPECT_FALSE(results["tests"].empty()) << id;
    double points = 0, max_points = 0;
    for (const auto& t : results["tests"]) points += t["points"].get<double>(), max_points += t["max_points"].get<double>();
    EXPECT_DOUBLE_EQ(results["score"].get<double>(), max_points > 0 ? points / max_points : 1.0)
        << id << ": a part worth no points shows 100%, not a red 0%";
    RecordProperty(id + " score", results["score"].dump());
  }
  for (const auto& f : fs::directory_iterator(hand_in)) EXPECT_TRUE(placed.count(f.path().filename().string())) << f.path().filename() << " has no question";
}
