// gradescope/: run_autograder as Gradescope runs it, against folders laid out like Gradescope's
// (AUTOGRADER_ROOT with submission/ and results/), with the real shadelab binary and its render
// workers; and the zip a TA uploads.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <zip.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <set>

#include <nlohmann/json.hpp>

#include "core/base64.h"
#include "support/files.h"
#include "support/hand_in.h"
#include "support/http_fixture.h"
#include "support/run_command.h"
#include "support/test_support.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const fs::path kSource = SHADELAB_SOURCE_DIR;

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

class GradescopeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("shadelab_gradescope_" + std::to_string(::getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_ / "submission");
    // One reference store for the suite, as setup.sh's warmed store serves every student: the
    // store is content-addressed and written by rename, so the tests' processes share it safely.
    const fs::path store = fs::temp_directory_path() / "shadelab_gradescope_test_references";
    fs::create_directories(store);
    fs::create_directories(root_ / "source");
    fs::create_directory_symlink(store, root_ / "source/reference-store");
  }
  void TearDown() override { fs::remove_all(root_); }

  void submit(const std::string& name, const std::string& text) const { shadelab::testkit::write_file_at(root_ / "submission" / name, text); }
  void submit_preset(const std::string& name, const std::string& preset, const std::string& stage) const {
    submit(name, shadelab::testkit::preset_module(preset, stage));
  }
  void save_frames(const std::string& folder, const std::string& preset, const std::string& prefix, const std::string& more = "",
                   const std::string& angles = shadelab::testkit::kPageAngles) const {
    shadelab::testkit::save_page_frames(root_ / "submission" / folder, preset, prefix, more, angles);
  }
  void hand_in(const std::string& specular_frames = "specular", const std::string& specular_code = "specular") const {
    shadelab::testkit::write_hand_in(root_ / "submission", specular_frames, specular_code);
  }

  // Gradescope's run: the environment names the folders; the results file is what it reads.
  json autograde() const {
    const std::string command = "AUTOGRADER_ROOT='" + root_.string() + "' SHADELAB_BIN='" + SHADELAB_CLI + "' bash '" +
                                (kSource / "gradescope/run_autograder").string() + "' >/dev/null 2>&1";
    EXPECT_EQ(run(command), 0);
    const std::string text = shadelab::testkit::read_text(root_ / "results/results.json");
    json results = json::parse(text, nullptr, false);
    EXPECT_FALSE(results.is_discarded()) << text;
    return results;
  }

  // A deliverable's test by what it grades: "saved frames", "code", "code under a hidden light",
  // "saved frames made by your code".
  static const json* test_of(const json& results, const std::string& checkpoint, const std::string& what) {
    const std::string name = title(checkpoint) + ": " + what;
    for (const auto& t : results["tests"]) {
      const std::string n = t["name"];
      if (n == name || n.starts_with(name + " (")) return &t;
    }
    return nullptr;
  }
  static std::string output_of(const json* test) { return test ? (*test)["output"].get<std::string>() : std::string(); }
  static const json* test_named(const json& results, const std::string& prefix) {
    for (const auto& t : results["tests"])
      if (t["name"].get<std::string>().starts_with(prefix)) return &t;
    return nullptr;
  }
  // What Gradescope shows for a checkpoint's test: the course's title for it.
  static std::string title(const std::string& checkpoint) { return shadelab::testkit::course().checkpoint(checkpoint)->checkpoint->title; }

  fs::path root_;
};

}  // namespace

// The diffuse reference's frames as ShadeLab draws them at the exact angles (what
// GET /api/render?preset=diffuse&output=frames gives a staff key), handed in as the deliverable's:
// no browser draws them, and the course wants frames saved from its page.
TEST_F(GradescopeTest, ShadeLabsOwnFramesOfTheReferenceScoreZeroAndAreFlagged) {
  hand_in();
  save_frames("HW2/images", "diffuse", "diffuse", "", "0,20,40,60,80,100,120,140,160");  // over the page's
  const json results = autograde();
  const json* frames = test_of(results, "diffuse", "saved frames");
  ASSERT_NE(frames, nullptr) << results.dump(2);
  EXPECT_EQ((*frames)["score"], 0) << output_of(frames);
  EXPECT_NE(output_of(frames).find("FLAGGED FOR THE TA: made by ShadeLab, not saved from the page"), std::string::npos) << output_of(frames);
  EXPECT_NE(output_of(frames).find("saved from its page"), std::string::npos) << output_of(frames);
  EXPECT_NE(results["output"].get<std::string>().find("FLAGGED FOR THE TA (diffuse saved frames): made by ShadeLab"), std::string::npos)
      << results["output"];
  // The page's own frames beside them: no flag.
  EXPECT_EQ(output_of(test_of(results, "normals", "saved frames")).find("FLAGGED"), std::string::npos);
  EXPECT_EQ((*test_of(results, "normals", "saved frames"))["status"], "passed");
}

// The student's HW2 folder as they zip it (the course's layout: src/shaders/ and images/), macOS
// litter included: each deliverable's saved frames, its code, the hidden-light rule and whether the
// frames are the code's, each its own test worth its share of the course's points.
TEST_F(GradescopeTest, TheHomeworkFolderIsGradedDeliverableByDeliverable) {
  hand_in();
  submit("HW2/src/hw2.js", "// the page's script\n");
  submit("__MACOSX/HW2/src/shaders/._phong_vert.js", "\x00\x05\x16\x07 resource fork");
  const json results = autograde();
  double points = 0;
  for (const auto& c : shadelab::testkit::course().checkpoints) points += c.points;
  EXPECT_EQ(results["score"], points) << results.dump(2);
  // normals: frames, code, match; diffuse: frames; specular: frames, code, probe, match; the three
  // dolly-zoom cameras and the Eevee render (0 points: for the TA).
  ASSERT_EQ(results["tests"].size(), 12u) << results.dump(2);
  for (const auto& t : results["tests"]) {
    EXPECT_EQ(t["status"], "passed") << t["name"] << ": " << t["output"];
    EXPECT_EQ(t["visibility"], "visible");
  }
  const json* code = test_of(results, "normals", "code");
  ASSERT_TRUE(code);
  EXPECT_EQ((*code)["name"], title("normals") + ": code (HW2/src/shaders/starter_vert.js, starter_frag.js)");
  const json* frames = test_of(results, "specular", "saved frames");
  ASSERT_TRUE(frames);
  EXPECT_EQ((*frames)["name"], title("specular") + ": saved frames (HW2/images/hw2_specular_0.png, ...)");
  // The weights are the profile's: the frames twice a code test's share.
  EXPECT_DOUBLE_EQ((*frames)["max_score"].get<double>(), 2 * (*test_of(results, "specular", "code"))["max_score"].get<double>());
  const json* probe = test_of(results, "specular", "code under a hidden light");
  ASSERT_TRUE(probe);
  EXPECT_NE(output_of(probe).find("N.L > 0"), std::string::npos) << "the rule it checks, in words: " << output_of(probe);
  EXPECT_NE(output_of(test_of(results, "specular", "saved frames made by your code")).find("what your code renders"), std::string::npos);
  EXPECT_FALSE(fs::exists(root_ / "results/heatmaps")) << "no test failed";
}

// Frames saved before the specular term was written (made by a diffuse-only shader) under the
// specular names, with the finished code: the frames fail as missing the highlight, and are said
// not to be what the code renders.
TEST_F(GradescopeTest, StaleSpecularFramesAreCaughtAndNamed) {
  hand_in("diffuse", "specular");
  const json results = autograde();
  const json* frames = test_of(results, "specular", "saved frames");
  ASSERT_TRUE(frames) << results.dump(2);
  EXPECT_EQ((*frames)["score"], 0.0);
  EXPECT_NE(output_of(frames).find("specular highlight missing"), std::string::npos) << output_of(frames).substr(0, 400);
  EXPECT_EQ((*frames)["output_format"], "html") << "the heat map, embedded";
  EXPECT_TRUE(fs::exists(root_ / "results/heatmaps/specular_frames.png"));
  const json* code = test_of(results, "specular", "code");
  ASSERT_TRUE(code);
  EXPECT_EQ((*code)["status"], "passed");
  const json* match = test_of(results, "specular", "saved frames made by your code");
  ASSERT_TRUE(match);
  EXPECT_EQ((*match)["score"], 0.0);
  EXPECT_NE(output_of(match).find("saved from an earlier version of your code"), std::string::npos) << output_of(match);
}

// The specular frames saved under the diffuse names: the diffuse deliverable's test says they look
// like the specular deliverable's frames.
TEST_F(GradescopeTest, SpecularFramesUnderTheDiffuseNamesAreNamedForWhatTheyAre) {
  hand_in();
  save_frames("HW2/images", "specular", "diffuse");  // over the diffuse frames
  const json results = autograde();
  const json* frames = test_of(results, "diffuse", "saved frames");
  ASSERT_TRUE(frames) << results.dump(2);
  EXPECT_EQ((*frames)["score"], 0.0);
  EXPECT_NE(output_of(frames).find("look like the specular deliverable's frames (hw2_specular_0.png"), std::string::npos)
      << output_of(frames).substr(0, 400);
}

// Frames saved at another size than the course's canvas: the file and both sizes are named.
TEST_F(GradescopeTest, FramesOfAnotherSizeSaySo) {
  hand_in("");
  save_frames("HW2/images", "specular", "specular", "--size 640x480");
  const json results = autograde();
  const json* frames = test_of(results, "specular", "saved frames");
  ASSERT_TRUE(frames) << results.dump(2);
  EXPECT_EQ((*frames)["score"], 0.0);
  EXPECT_NE(output_of(frames).find("hw2_specular_0.png is 640 x 480; the course's canvas is 512 x 512"), std::string::npos) << output_of(frames);
  EXPECT_EQ((*test_of(results, "normals", "saved frames"))["status"], "passed") << "the other deliverables are graded as usual";
}

// A frame missing, and a frame saved twice in place of the next.
TEST_F(GradescopeTest, AMissingFrameAndARepeatedFrameAreNamed) {
  hand_in();
  fs::remove(root_ / "submission/HW2/images/hw2_normals_4.png");
  fs::copy_file(root_ / "submission/HW2/images/hw2_specular_2.png", root_ / "submission/HW2/images/hw2_specular_3.png",
                fs::copy_options::overwrite_existing);
  const json results = autograde();
  const json* normals = test_of(results, "normals", "saved frames");
  ASSERT_TRUE(normals) << results.dump(2);
  EXPECT_EQ((*normals)["score"], 0.0);
  EXPECT_NE(output_of(normals).find("hw2_normals_4.png is missing"), std::string::npos) << output_of(normals);
  const json* specular = test_of(results, "specular", "saved frames");
  ASSERT_TRUE(specular);
  EXPECT_EQ((*specular)["score"], 0.0);
  EXPECT_NE(output_of(specular).find("hw2_specular_3.png shows frame 2's rotation"), std::string::npos) << output_of(specular).substr(0, 400);
}

// The modules alone, the specular stage not done: the missing checkpoint says what was looked
// for, the failed one says what is wrong and shows where.
TEST_F(GradescopeTest, AMissingAndAWrongCheckpointSayWhy) {
  submit_preset("phong_vert.js", "diffuse", "vert");
  submit_preset("phong_frag.js", "diffuse", "frag");
  const json results = autograde();
  EXPECT_EQ(results["score"], 0.0) << results.dump(2);
  const json* normals = test_of(results, "normals", "code");
  ASSERT_TRUE(normals) << results.dump(2);
  EXPECT_EQ((*normals)["score"], 0.0);
  EXPECT_NE((*normals)["output"].get<std::string>().find("expected starter_vert.js and starter_frag.js"), std::string::npos);
  EXPECT_NE((*normals)["output"].get<std::string>().find("the submission has phong_frag.js, phong_vert.js"), std::string::npos)
      << (*normals)["output"];
  const json* frames = test_of(results, "normals", "saved frames");
  ASSERT_TRUE(frames);
  EXPECT_NE(output_of(frames).find("no saved frames: expected hw2_normals_0.png to hw2_normals_8.png"), std::string::npos) << output_of(frames);
  const json* specular = test_named(results, title("specular") + ": code (phong_vert.js, phong_frag.js)");
  ASSERT_TRUE(specular) << results.dump(2);
  EXPECT_EQ((*specular)["status"], "failed");
  const std::string output = (*specular)["output"];
  EXPECT_NE(output.find("specular highlight missing"), std::string::npos) << output.substr(0, 300);
  EXPECT_EQ((*specular)["output_format"], "html");
  EXPECT_NE(output.find("<img alt=\"difference heat map\""), std::string::npos);
  EXPECT_NE(output.find("src=\"data:image/png;base64,iVBORw0KGgo"), std::string::npos) << "a PNG, embedded";
  const std::string png = shadelab::testkit::read_text(root_ / "results/heatmaps/specular.png");
  EXPECT_TRUE(png.starts_with("\x89PNG")) << "the heat map is kept beside results.json";
}

TEST_F(GradescopeTest, ASubmissionThatDoesNotCompileScoresZeroWithItsError) {
  std::string broken = shadelab::testkit::read_text(kSource / "shaders/normals_vert.js");
  const size_t at = broken.find("void main");
  broken.replace(at, 9, "void main(");  // a syntax error inside main's signature
  const long main_line = 1 + std::count(broken.begin(), broken.begin() + static_cast<long>(at), '\n');
  submit("starter_vert.js", broken);
  submit_preset("starter_frag.js", "normals", "frag");
  const json results = autograde();
  const json* normals = test_of(results, "normals", "code");
  ASSERT_TRUE(normals) << results.dump(2);
  EXPECT_EQ((*normals)["score"], 0.0);
  EXPECT_EQ((*normals)["status"], "failed");
  EXPECT_NE((*normals)["output"].get<std::string>().find("compile error at starter_vert.js line " + std::to_string(main_line)), std::string::npos)
      << "the error at the student's file and line: " << (*normals)["output"];
}

// A link in the submission is not followed: the grader would read (and quote in its diagnostics)
// a file of the autograder's image.
TEST_F(GradescopeTest, ALinkInTheSubmissionIsNotFollowed) {
  const fs::path outside = root_ / "outside_vert.js";
  std::ofstream(outside) << shadelab::testkit::read_text(kSource / "shaders/normals_vert.js");
  fs::create_symlink(outside, root_ / "submission/starter_vert.js");
  submit_preset("starter_frag.js", "normals", "frag");
  const json results = autograde();
  const json* normals = test_of(results, "normals", "code");
  ASSERT_TRUE(normals) << results.dump(2);
  EXPECT_EQ((*normals)["score"], 0.0) << "graded through the link";
  EXPECT_NE((*normals)["output"].get<std::string>().find("the submission has starter_frag.js\n"), std::string::npos)
      << (*normals)["output"];
}

// The dolly zoom's cameras checked (grade/camera_check.h): one image saved for two cameras fails
// its test, 0 points of 0 (for the TA), in the same words on Gradescope and on the sheet.
TEST_F(GradescopeTest, ACameraSavedTwiceReadsTheSameOnGradescopeAndOnTheSheet) {
  hand_in();
  submit("HW2/images/camera_100.png", shadelab::testkit::read_text(kSource / "tests/blender_half/blender_camera_50.png"));
  const json results = autograde();
  const json* hundred = test_named(results, "Dolly zoom: 100 mm (images/camera_100.png)");
  ASSERT_NE(hundred, nullptr) << results.dump(2);
  EXPECT_EQ((*hundred)["status"], "failed");
  EXPECT_EQ((*hundred)["max_score"], 0.0);
  const std::string output = output_of(hundred);
  const std::string verdict = output.substr(output.find('\n') + 1, output.size() - output.find('\n') - 2);
  EXPECT_TRUE(verdict.starts_with("the same image as images/camera_50.png: shows a 50 mm lens at (0, -8, 0)")) << output;
  EXPECT_EQ((*test_named(results, "Dolly zoom: 50 mm"))["status"], "passed");
  const auto sheet = shadelab::testkit::run_shadelab("sheet '" + (root_ / "submission/HW2").string() + "' -o '" + (root_ / "sheet.pdf").string() + "'");
  ASSERT_EQ(sheet.status, 0) << sheet.output;
  EXPECT_NE(sheet.output.find("Dolly zoom: 100 mm: 0 / 0 (for the TA): " + verdict + "\n"), std::string::npos) << sheet.output << "\n" << verdict;
}

// The HTML's text as written (the sheet escapes <, >, & and ").
std::string unescaped(std::string html) {
  for (const auto& [from, to] : {std::pair{"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&amp;", "&"}})
    for (size_t at; (at = html.find(from)) != std::string::npos;) html.replace(at, std::string(from).size(), to);
  return html;
}

// What `shadelab sheet` prints after the PDF for `key` (a checkpoint's name or an image's title):
// the line "<key>: <verdict>"'s verdict; empty when there is none.
std::string printed_verdict(const std::string& output, const std::string& key) {
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);)
    if (line.starts_with(key + ": ")) return line.substr(key.size() + 2);
  return {};
}

// One hand-in, four roads: Gradescope's run_autograder, `shadelab autograde`, `shadelab sheet` and
// POST /api/sheet give each deliverable and each checked image the same score and the same words.
// The hand-in fails somewhere (stale specular frames; one camera saved twice) so that the words
// compared are a failure's, not only "matches".
TEST_F(GradescopeTest, TheSameHandInReadsTheSameOnEveryRoad) {
  hand_in("diffuse", "specular");
  submit("HW2/images/camera_100.png", shadelab::testkit::read_text(kSource / "tests/blender_half/blender_camera_50.png"));
  const json gradescope = autograde();
  const fs::path folder = root_ / "submission/HW2";

  const auto direct = shadelab::testkit::run_shadelab("autograde '" + (root_ / "submission").string() + "' --results '" +
                                                      (root_ / "direct.json").string() + "' --heatmaps '" + (root_ / "direct_heatmaps").string() +
                                                      "' --cache-dir '" + (root_ / "source/reference-store").string() + "'");
  ASSERT_EQ(direct.status, 0) << direct.output;
  json cli = json::parse(shadelab::testkit::read_text(root_ / "direct.json"));
  ASSERT_EQ(cli["tests"].size(), gradescope["tests"].size());
  EXPECT_EQ(cli["score"], gradescope["score"]);
  for (size_t i = 0; i < cli["tests"].size(); ++i)
    for (const char* field : {"name", "score", "max_score", "status", "output"})
      EXPECT_EQ(cli["tests"][i][field], gradescope["tests"][i][field]) << field << " of " << cli["tests"][i]["name"];

  const auto printed = shadelab::testkit::run_shadelab("sheet '" + folder.string() + "' -o '" + (root_ / "sheet.pdf").string() + "' --cache-dir '" +
                                                       (root_ / "source/reference-store").string() + "'");
  ASSERT_EQ(printed.status, 0) << printed.output;

  json files = json::object(), images = json::object();
  for (const auto& e : fs::recursive_directory_iterator(folder)) {
    if (!e.is_regular_file()) continue;
    const std::string path = "HW2/" + fs::relative(e.path(), folder).generic_string();
    if (e.path().extension() == ".png") images[path] = shadelab::base64_encode(shadelab::testkit::read_text(e.path()));
    else files[path] = shadelab::testkit::read_text(e.path());
  }
  shadelab::testkit::RunningService server(shadelab::testkit::test_config());
  ASSERT_TRUE(server.ok()) << server.failure;
  auto page = server.client().Post("/api/sheet", json{{"files", files}, {"images", images}, {"format", "html"}}.dump(), "application/json");
  ASSERT_TRUE(page);
  ASSERT_EQ(page->status, 200) << page->body.substr(0, 400);
  const std::string html = unescaped(page->body);

  for (const auto& c : shadelab::testkit::course().checkpoints) {
    SCOPED_TRACE(c.name);
    const std::string verdict = printed_verdict(printed.output, c.name);  // "0.4 / 1: <words>"
    ASSERT_FALSE(verdict.empty()) << printed.output;
    double score = -1, points = -1;
    ASSERT_EQ(std::sscanf(verdict.c_str(), "%lf / %lf", &score, &points), 2) << verdict;
    double on_gradescope = 0, of = 0;
    bool words_there = false;
    const std::string words = verdict.substr(verdict.find(": ") + 2);
    for (const auto& t : gradescope["tests"])
      if (t["name"].get<std::string>().starts_with(c.title + ":")) {
        on_gradescope += t["score"].get<double>(), of += t["max_score"].get<double>();
        words_there |= t["output"].get<std::string>().find(words) != std::string::npos;
      }
    EXPECT_NEAR(on_gradescope, score, 1e-9) << verdict;
    EXPECT_NEAR(of, points, 1e-9) << verdict;
    EXPECT_TRUE(words_there) << "Gradescope's tests of " << c.title << " do not say: " << words;
    EXPECT_NE(html.find("\">" + verdict + "</p>"), std::string::npos) << verdict;
  }
  for (const auto& wanted : shadelab::testkit::course().images) {
    if (!wanted.checked()) continue;
    SCOPED_TRACE(wanted.file);
    const std::string verdict = printed_verdict(printed.output, wanted.title);  // "0 / 0 (for the TA): <words>"
    ASSERT_FALSE(verdict.empty()) << printed.output;
    const json* test = test_named(gradescope, wanted.title);
    ASSERT_TRUE(test);
    EXPECT_NE(output_of(test).find(verdict.substr(verdict.find(": ") + 2)), std::string::npos) << output_of(test) << "\n" << verdict;
    EXPECT_NE(html.find("\">" + verdict + "</p>"), std::string::npos) << verdict;
  }
  EXPECT_NE(printed_verdict(printed.output, "specular").find("specular highlight missing"), std::string::npos) << "a failure's words were compared";
  EXPECT_NE(printed_verdict(printed.output, shadelab::testkit::course().images[2].title).find("the same image as"), std::string::npos);
}

TEST_F(GradescopeTest, AnEmptySubmissionScoresZeroAndSaysSo) {
  const json results = autograde();
  EXPECT_EQ(results["score"], 0.0);
  ASSERT_EQ(results["tests"].size(), 12u) << results.dump(2);
  for (const auto& t : results["tests"]) {
    EXPECT_EQ(t["score"], 0.0);
    const std::string output = t["output"];
    EXPECT_TRUE(output.find("the submission has nothing") != std::string::npos || output.find("these PNGs: nothing") != std::string::npos ||
                output.find("not compared") != std::string::npos || output.find("no shaders for this deliverable") != std::string::npos ||
                output.find("\nnot in the submission.\n") != std::string::npos)
        << t["name"] << ": " << output;
  }
}

// A TA's own course profile shipped in the zip (source/course/course.json): run_autograder grades
// by it. Here the built-in profile with the normals checkpoint renamed in words and worth 2 points.
TEST_F(GradescopeTest, TheCourseInTheZipIsTheOneGradedBy) {
  const auto shown = shadelab::testkit::run_shadelab("course show");
  ASSERT_EQ(shown.status, 0) << shown.output;
  json profile = json::parse(shown.output);
  profile["checkpoints"][0]["title"] = "Part 1: normals";
  profile["checkpoints"][0]["points"] = 2;
  fs::create_directories(root_ / "source/course");
  std::ofstream(root_ / "source/course/course.json") << profile.dump(2);
  submit_preset("starter_vert.js", "normals", "vert");
  submit_preset("starter_frag.js", "normals", "frag");
  const json results = autograde();
  const json* part1 = test_named(results, "Part 1: normals: code");
  ASSERT_TRUE(part1) << results.dump(2);
  // 2 points shared by the frames (2 shares), the code (1) and the match (1).
  EXPECT_EQ((*part1)["max_score"], 0.5);
  EXPECT_EQ((*part1)["score"], 0.5);
}

// setup.sh renders the course's references and known mistakes once (warm_references.sh, run here
// as setup.sh runs it): grading a student then reads them, and renders only the student's frames,
// even for a failing submission whose diagnosis needs the whole catalogue.
TEST_F(GradescopeTest, AStoreWarmedAtSetupMeansNoReferenceIsRenderedPerStudent) {
  // A store of its own, empty: in the suite's shared one, renders other tests left would hide a
  // warm that leaves them out (it did: the formula's geometry and the catalogue, which a student
  // whose frames no repair explains reads, were rendered at the first such student's grade).
  fs::remove(root_ / "source/reference-store");
  fs::create_directories(root_ / "source/reference-store");
  const std::string env = "AUTOGRADER_ROOT='" + root_.string() + "' SHADELAB_BIN='" + SHADELAB_CLI + "' ";
  const auto warmed = shadelab::testkit::run_command(env + "bash '" + (kSource / "gradescope/warm_references.sh").string() + "'");
  ASSERT_EQ(warmed.status, 0) << warmed.output;
  submit_preset("starter_vert.js", "normals", "vert");
  submit_preset("starter_frag.js", "normals", "frag");
  submit_preset("phong_vert.js", "diffuse", "vert");  // the specular stage not done: fails, diagnosed
  submit_preset("phong_frag.js", "diffuse", "frag");
  save_frames("images", "normals", "normals");
  const json results = autograde();
  for (const std::string what : {"code", "code under a hidden light"}) {
    const json* t = test_of(results, what == "code" ? "normals" : "specular", what);
    ASSERT_TRUE(t) << what << ": " << results.dump(2);
    const json& work = (*t)["extra_data"]["graderWork"];
    EXPECT_EQ(work["rendered"], 0) << (*t)["name"] << ": " << work;
    EXPECT_GT(work["fromStore"].get<int>(), 0) << (*t)["name"] << ": " << work;
  }
  // Saved frames: the lag grid from the store, and one render of the job at the angles found.
  const json& frames_work = (*test_of(results, "normals", "saved frames"))["extra_data"]["graderWork"];
  EXPECT_EQ(frames_work["rendered"], 1) << frames_work;
  EXPECT_EQ(frames_work["fromStore"], 1) << frames_work;
  const json* specular = test_of(results, "specular", "code");
  ASSERT_TRUE(specular);
  EXPECT_NE((*specular)["output"].get<std::string>().find("specular highlight missing"), std::string::npos) << "diagnosed from the store";
}

// Without the grader installed the student still gets a results.json that says so.
TEST_F(GradescopeTest, AMissingGraderStillWritesResults) {
  const std::string command = "AUTOGRADER_ROOT='" + root_.string() + "' SHADELAB_BIN=/nonexistent/shadelab bash '" +
                              (kSource / "gradescope/run_autograder").string() + "' >/dev/null 2>&1";
  ASSERT_EQ(run(command), 0);
  const json results = json::parse(shadelab::testkit::read_text(root_ / "results/results.json"), nullptr, false);
  ASSERT_FALSE(results.is_discarded());
  EXPECT_EQ(results["score"], 0);
  EXPECT_NE(results["output"].get<std::string>().find("not installed at /nonexistent/shadelab"), std::string::npos);
}

// The zip a TA uploads: the committed sources, with setup.sh and run_autograder at its root.
TEST_F(GradescopeTest, TheAutograderZipHasGradescopesLayout) {
  if (!fs::exists(kSource / ".git")) GTEST_SKIP() << "not a git checkout (the zip is made with git archive)";
  const fs::path zip_path = root_ / "autograder.zip";
  ASSERT_EQ(run("bash '" + (kSource / "gradescope/make_autograder_zip.sh").string() + "' '" + zip_path.string() + "' >/dev/null"), 0);
  int error = 0;
  zip_t* zip = zip_open(zip_path.c_str(), ZIP_RDONLY, &error);
  ASSERT_TRUE(zip) << "libzip error " << error;
  std::set<std::string> names;
  for (zip_int64_t i = 0; i < zip_get_num_entries(zip, 0); ++i) names.insert(zip_get_name(zip, i, 0));
  zip_close(zip);
  for (const char* expected : {"setup.sh", "run_autograder", "CMakeLists.txt", "tools/setup.sh", "server/cli/main.cpp", "assets/bunny.obj",
                               "courses/cs148-summer2022.json"})
    EXPECT_TRUE(names.count(expected)) << expected;
}
