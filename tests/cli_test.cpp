// The shadelab executable end to end: exit codes, files written, compiler-style diagnostics.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "image/encode.h"
#include "image/png_decode.h"
#include "support/files.h"
#include "support/run_command.h"
#include "support/test_support.h"
#include "support/tutorial_program.h"

namespace fs = std::filesystem;

namespace {
using Run = shadelab::testkit::CommandRun;
Run run_cli(const std::string& args) { return shadelab::testkit::run_shadelab(args); }

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("shadelab_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write(const std::string& name, const std::string& text) const {
    fs::create_directories((dir_ / name).parent_path());
    std::ofstream(dir_ / name) << text;
  }
  fs::path dir_;
};

using shadelab::testkit::read_text;

std::vector<std::uint8_t> read_bytes(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}
}  // namespace

TEST_F(CliTest, RenderWritesTheThreeByThreeGridOfTheCoursesCanvas) {
  const auto run = run_cli("render --preset specular --mesh bunny --grid " + path("g.png"));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto img = shadelab::testkit::decode(read_bytes(path("g.png")));
  const auto& course = shadelab::testkit::course();
  EXPECT_EQ(img.width, 3 * course.width);
  EXPECT_EQ(img.height, 3 * course.height);
}

TEST_F(CliTest, FramesDirGetsTheHandoutsNames) {
  const auto run = run_cli("render --preset diffuse --mesh teapot --size 64x48 --frames-dir " + path("frames"));
  ASSERT_EQ(run.status, 0) << run.output;
  for (int k = 0; k < 9; ++k) EXPECT_TRUE(fs::exists(path("frames/hw2_diffuse_" + std::to_string(k) + ".png"))) << k;
  EXPECT_FALSE(fs::exists(path("frames/hw2_diffuse_9.png")));
}

TEST_F(CliTest, StudentFilesAndUniformsWork) {
  write("my_vert.js", "export default `#version 300 es\nin vec4 aVertexPosition;\nuniform mat4 uWorldToClipSpaceMatrix;\n"
                      "uniform mat4 uMeshToWorldMatrix;\nvoid main() { gl_Position = uWorldToClipSpaceMatrix * "
                      "uMeshToWorldMatrix * aVertexPosition; }\n`;\n");
  write("my_frag.js", "export default `#version 300 es\nprecision highp float;\nuniform vec4 diffuseColor;\n"
                      "out vec4 c;\nvoid main() { c = diffuseColor; }\n`;\n");
  const auto run = run_cli("render --vert " + path("my_vert.js") + " --frag " + path("my_frag.js") +
                            " --size 64x48 --frames 4 --uniform diffuseColor=0,0,1,1 --grid " + path("g.png"));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto img = shadelab::testkit::decode(read_bytes(path("g.png")));
  EXPECT_EQ(img.width, 128);  // 4 frames: 2 x 2
  bool blue = false;
  for (size_t i = 0; i < img.bytes.size(); i += 4) blue |= img.bytes[i + 2] == 255 && img.bytes[i] == 0;
  EXPECT_TRUE(blue);
}

TEST_F(CliTest, BrokenShaderPrintsCompilerStyleDiagnosticsAndFails) {
  write("broken_frag.js", "export default `#version 300 es\nprecision highp float;\nout vec4 c;\n"
                          "void main() { c = vec4(1.0) }\n`;\n");
  const auto run = run_cli("render --vert " + path("broken_frag.js") + " --frag " + path("broken_frag.js") +
                            " --grid " + path("g.png"));
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("broken_frag.js:4:"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("compile_failed"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(path("g.png")));
}

TEST_F(CliTest, BadArgumentsFailClearly) {
  auto run = run_cli("render --preset phong --grid " + path("g.png"));
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("unknown_preset"), std::string::npos) << run.output;
  run = run_cli("render --preset smooth --uniform uX=1,abc --grid " + path("g.png"));
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("not a number"), std::string::npos) << run.output;
  run = run_cli("render --preset smooth --mesh " + path("missing.obj"));
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("mesh_not_found"), std::string::npos) << run.output;
  run = run_cli("render --preset smooth --size big");
  EXPECT_EQ(run.status, 1);
}

TEST_F(CliTest, InfoNamesTheRenderer) {
  const auto run = run_cli("info");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("GL renderer:"), std::string::npos);
  EXPECT_NE(run.output.find("OpenGL ES 3"), std::string::npos);
}

// A worker that dies before it is ready (server/worker/fault_injection.h's start phase): the
// command fails with not_ready, saying how the worker ended, which the operator needs to tell a
// crash from a kill (the out-of-memory killer) or an exit.
TEST_F(CliTest, AWorkerThatDiesStartingSaysHowItEnded) {
  const std::string shaders = std::string(SHADELAB_SOURCE_DIR) + "/shaders/";
  const std::vector<std::pair<std::string, std::string>> faults = {
      {"crash", "signal Segmentation fault"}, {"kill", "signal Killed"}, {"truncate", "exit status 3"}};
  for (const auto& [action, how] : faults) {
    const auto run = shadelab::testkit::run_command("SHADELAB_FAULT_INJECTION=" + path("faults.log") + " SHADELAB_FAULT_AT_START=" + action +
                                                    " " + SHADELAB_CLI + " grade --vert " + shaders + "specular_vert.js --frag " + shaders +
                                                    "specular_frag.js --reference specular");
    EXPECT_EQ(run.status, 1) << action << ": " << run.output;
    EXPECT_NE(run.output.find("a render worker could not start: it exited while starting (" + how + ") [not_ready]"), std::string::npos)
        << action << ": " << run.output;
  }
  // Without the fault-injection log the variable is ignored: nothing a deployment sets by mistake.
  const auto run = shadelab::testkit::run_command("SHADELAB_FAULT_AT_START=crash " + std::string(SHADELAB_CLI) + " grade --vert " + shaders +
                                                  "specular_vert.js --frag " + shaders + "specular_frag.js --reference specular");
  EXPECT_EQ(run.status, 0) << run.output;
}

TEST_F(CliTest, ExrOutputIsFloat) {
  const auto run = run_cli("render --preset smooth --size 32x24 --frames 1 --format exr --grid " + path("g.exr"));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto img = shadelab::testkit::decode(read_bytes(path("g.exr")));
  EXPECT_EQ(img.type, shadelab::image::PixelType::f32);
  EXPECT_EQ(img.width, 32);
}

// Other processes keeping every core busy for as long as it lives.
class CpuBurners {
 public:
  CpuBurners() {
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    for (unsigned i = 0; i < cores; ++i) {
      const pid_t pid = ::fork();
      if (pid == 0) {
        volatile unsigned long spin = 0;
        while (true) spin = spin + 1;
      }
      pids_.push_back(pid);
    }
  }
  ~CpuBurners() {
    for (pid_t pid : pids_) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  }

 private:
  std::vector<pid_t> pids_;
};

// A hostile student's folder name cannot forge a row of the TA's table, hide the batch's last
// lines, run as a spreadsheet formula, take the place of the batch's own files, or grade another
// student's folder through a link (docs/reliability.md, "The attacker").
TEST_F(CliTest, HostileFolderNamesCannotForgeTheTasTable) {
  for (const char* name : {"alice", "zoe\ralice", "=HYPERLINK(\"x\")", "summary.csv", "graded.jsonl", "esc\x1b[8mhidden"})
    fs::create_directories(dir_ / "class" / name);  // each handed in nothing: graded 0 without a render
  fs::create_directory_symlink(dir_ / "class" / "alice", dir_ / "class" / "mallory");
  // fred's fragment shader is named with an escape code, and does not compile: his results name it.
  write("class/fred/phong_vert.js", read_text(std::string(SHADELAB_SOURCE_DIR) + "/shaders/specular_vert.js"));
  write("class/fred/phong\x1b[8m_frag.js", "export default `#version 300 es\nvod main() {}\n`;\n");
  const auto run = run_cli("grade --submissions " + path("class") + " --reference specular --size 64x48 --out " + path("grades"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("refused: mallory is a symbolic link"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find('\x1b'), std::string::npos) << "an escape code reached the terminal";
  const std::string summary = read_text(path("grades/summary.csv"));
  std::vector<std::string> rows;
  for (std::istringstream lines(summary); std::getline(lines, rows.emplace_back());) {}
  rows.pop_back();
  EXPECT_EQ(rows.size(), 8u) << summary;  // the header and seven students: no row forged, mallory not graded
  EXPECT_EQ(std::count_if(rows.begin(), rows.end(), [](const std::string& r) { return r.starts_with("alice,"); }), 1) << summary;
  EXPECT_EQ(summary.find('\r'), std::string::npos) << summary;
  EXPECT_NE(summary.find("zoe\\x0Dalice,"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"'=HYPERLINK(\"\"x\"\")\","), std::string::npos) << summary;
  EXPECT_NE(summary.find("esc\\x1B[8mhidden,"), std::string::npos) << summary;
  EXPECT_TRUE(fs::is_regular_file(dir_ / "grades" / "students" / "summary.csv" / "results.json"));
  EXPECT_TRUE(fs::is_regular_file(dir_ / "grades" / "students" / "graded.jsonl" / "results.json"));
  EXPECT_FALSE(fs::exists(dir_ / "grades" / "students" / "mallory"));
  const std::string fred = read_text(path("grades/students/fred/results.json"));
  EXPECT_EQ(fred.find("\\u001b"), std::string::npos) << fred;
  EXPECT_NE(fred.find("phong\\\\x1B[8m_frag.js"), std::string::npos) << fred;
}

// The deadline counts the worker's CPU time: with every core taken by other processes the correct
// submissions are still graded, and the hanging one is 0 only after a second attempt.
TEST_F(CliTest, BatchGradingScoresAHangingSubmissionZeroAndGoesOn) {
  const auto preset = [](const std::string& f) { return read_text(std::string(SHADELAB_SOURCE_DIR) + "/shaders/" + f); };
  write("class/alice/shaders/phong_vert.js", preset("specular_vert.js"));
  write("class/alice/shaders/phong_frag.js", preset("specular_frag.js"));
  write("class/bob/shaders/phong_vert.js", preset("diffuse_vert.js"));
  write("class/bob/shaders/phong_frag.js", preset("diffuse_frag.js"));
  std::string hang = preset("specular_frag.js");
  hang.replace(hang.find("    fragColor = color;"), 22,
               "    float s = gl_FragCoord.x;\n    while (true) { s = sin(s); if (s > 2.0) break; }\n    fragColor = color + vec4(s);");
  write("class/carol/shaders/phong_vert.js", preset("specular_vert.js"));
  write("class/carol/shaders/phong_frag.js", hang);
  fs::create_directories(dir_ / "class" / "dave");  // handed in nothing

  const CpuBurners busy;
  const auto run = run_cli("grade --submissions " + path("class") + " --reference specular --size 64x48 --timeout-ms 2000 --out " +
                           path("grades"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("4/4"), std::string::npos);  // the progress bar reached the end
  const std::string summary = read_text(path("grades/summary.csv"));
  EXPECT_NE(summary.find("alice,1.000000,1.000000,true"), std::string::npos) << summary;
  EXPECT_NE(summary.find("bob,0.000000,1.000000,false,missing_specular"), std::string::npos) << summary;
  EXPECT_NE(summary.find("carol,0.000000,1.000000,false,render_timeout"), std::string::npos) << summary;
  EXPECT_NE(summary.find("dave,0.000000,1.000000,false,invalid_argument,\"no shader pair found for specular: expected phong_vert.js"),
            std::string::npos) << summary;
  for (const char* who : {"alice", "bob", "carol", "dave"}) {
    const auto results = nlohmann::json::parse(read_text(path(std::string("grades/students/") + who + "/results.json")));
    EXPECT_TRUE(results.contains("score") && results.contains("execution_time") && results.contains("tests")) << who;
  }
  const std::string carol = read_text(path("grades/students/carol/results.json"));
  // Stopped by its CPU budget, or, where this machine is so oversubscribed that the worker gets
  // under a quarter of a core, by the wall-clock backstop: either way only after a second attempt.
  EXPECT_NE(carol.find("graded again"), std::string::npos) << carol;
}

// A class's failing students are counted by their mistake: where the repair search confirmed one,
// by its label (never the line, nor the student's own name for a vector, which differ between
// students), beside the formula's labels.
TEST_F(CliTest, BatchCountsFailingStudentsByTheirRepair) {
  const auto preset = [](const std::string& f) { return read_text(std::string(SHADELAB_SOURCE_DIR) + "/shaders/" + f); };
  const auto replaced = [](std::string text, const std::string& find, const std::string& with) {
    text.replace(text.find(find), find.size(), with);
    return text;
  };
  const std::string right = "vec3 L = normalize(uLightPosition - vPosition);";
  write("class/ivan/shaders/phong_vert.js", preset("specular_vert.js"));
  write("class/ivan/shaders/phong_frag.js", replaced(preset("specular_frag.js"), right, "vec3 L = uLightPosition - vPosition;"));
  // judy made ivan's mistake one line further down, and calls the direction to the light toLight.
  std::string judy = replaced(preset("specular_frag.js"), right, "\nvec3 toLight = uLightPosition - vPosition;");
  judy = replaced(replaced(judy, "dot(N, L)", "dot(N, toLight)"), "reflect(-L, N)", "reflect(-toLight, N)");
  write("class/judy/shaders/phong_vert.js", preset("specular_vert.js"));
  write("class/judy/shaders/phong_frag.js", judy);
  write("class/kim/shaders/phong_vert.js", preset("specular_vert.js"));
  write("class/kim/shaders/phong_frag.js", preset("specular_frag.js"));
  // leo made ivan's mistake and changed the exponent too: counted by both, apart from ivan and judy.
  std::string leo = preset("specular_frag.js");
  leo.replace(leo.find(right), right.size(), "vec3 L = uLightPosition - vPosition;");
  leo.replace(leo.find("float specularAlpha = 6.0;"), 26, "float specularAlpha = 20.0;");
  write("class/leo/shaders/phong_vert.js", preset("specular_vert.js"));
  write("class/leo/shaders/phong_frag.js", leo);
  const auto run = run_cli("grade --submissions " + path("class") + " --reference specular --size 64x48 --out " + path("grades"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("2 students: L not normalised\n"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("1 student: L not normalised + `20.0` not the homework's number"), std::string::npos) << run.output;
  const std::string explanations = read_text(path("grades/explanations.csv"));
  EXPECT_NE(explanations.find("L not normalised,2,ivan judy\n"), std::string::npos) << explanations;
  // Each student still reads the words of their own program, at their own line.
  const std::string judy_results = read_text(path("grades/students/judy/results.json"));
  EXPECT_NE(judy_results.find("`toLight` is not normalised: the direction to the light must be a unit vector"), std::string::npos);
  // Her results.json is hers (Gradescope shows it to her): where the line is, as the course's
  // repairShown says, never the repaired line itself.
  EXPECT_EQ(judy_results.find("normalize(uLightPosition - vPosition)"), std::string::npos) << judy_results;
  EXPECT_EQ(judy_results.find("the frames match the reference's"), std::string::npos) << judy_results;
  // What each grade cost, counted: kim's program drawn once; ivan's, and its repair confirmed by
  // a render of its own; and the class's sum said on the batch's last lines.
  std::map<std::string, nlohmann::json> journal;
  std::istringstream lines(read_text(path("grades/graded.jsonl")));
  for (std::string line; std::getline(lines, line);) journal[nlohmann::json::parse(line)["student"]] = nlohmann::json::parse(line);
  EXPECT_EQ(journal["kim"]["renders"], 1);
  EXPECT_EQ(journal["kim"]["screened"], 0);
  EXPECT_EQ(journal["ivan"]["renders"], 2);
  EXPECT_GE(journal["ivan"]["screened"].get<int>(), 1);
  int renders = 0, screened = 0;
  for (const auto& [who, j] : journal) renders += j["renders"].get<int>(), screened += j["screened"].get<int>();
  EXPECT_GE(journal["leo"]["screened"].get<int>(), journal["ivan"]["screened"].get<int>()) << "a pair is screened after the singles";
  char expected[160];
  std::snprintf(expected, sizeof expected, "the grader drew %d renders at the grade's frames (%.2f a student) and screened %d repair candidates",
                renders, renders / 4.0, screened);
  EXPECT_NE(run.output.find(expected), std::string::npos) << run.output;
}

// A failing student no search repaired beside the course's reference is searched again beside the
// class's passing programs: one written as the classmate's is (`reflectDir`, where the reference
// writes R) is repaired at their line, named and never shown, even on a TA's machine, where the
// classmate's line would be theirs to copy; one with two such mistakes by a pair of the class's;
// one the class offers nothing keeps their first grade, not drawn again. The journal says so and
// counts both passes; the same command run again grades nobody twice.
TEST_F(CliTest, BatchSearchesAgainBesideTheClassesPassingPrograms) {
  const auto preset = [](const std::string& f) { return read_text(std::string(SHADELAB_SOURCE_DIR) + "/shaders/" + f); };
  const std::string tutorial = shadelab::testkit::with_tutorial_main(preset("specular_frag.js"));
  // The half vector through a local of its own: two locals the reference's cannot align one to one
  // (repair/student_names.h), so that the reference alone offers no value for reflectDir.
  std::string half_vector = tutorial;
  const std::string reflect_dir = "vec3 reflectDir = reflect(-lightDir, norm);";
  half_vector.replace(half_vector.find(reflect_dir), reflect_dir.size(), "vec3 halfway = normalize(lightDir + viewDir);\n        vec3 reflectDir = halfway;");
  write("class/ana/shaders/phong_vert.js", preset("specular_vert.js"));
  write("class/ana/shaders/phong_frag.js", tutorial);
  write("class/ben/shaders/phong_vert.js", preset("specular_vert.js"));
  write("class/ben/shaders/phong_frag.js", half_vector);
  // cyd made ben's mistake and left the ambient out: ana's value and the ambient put back, a pair.
  std::string two = half_vector;
  two.replace(two.find("uAmbientColor + diff * uDiffuseColor"), 36, "diff * uDiffuseColor");
  write("class/cyd/shaders/phong_vert.js", preset("specular_vert.js"));
  write("class/cyd/shaders/phong_frag.js", two);
  // dee wrote the reference's names and made three mistakes: ana's values name locals dee never
  // declares, so the class offers nothing to try and dee's first grade stands, drawn once.
  std::string three = preset("specular_frag.js");
  three.replace(three.find("reflect(-L, N)"), 14, "normalize(L + V)");
  three.replace(three.find("uAmbientColor + uDiffuseColor"), 29, "uDiffuseColor");
  three.replace(three.find("specularAlpha = 6.0"), 19, "specularAlpha = 12.0");
  write("class/dee/shaders/phong_vert.js", preset("specular_vert.js"));
  write("class/dee/shaders/phong_frag.js", three);
  const std::string command = "grade --submissions " + path("class") + " --reference specular --size 64x48 --out " + path("grades");
  const auto run = run_cli(command);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("searching 3 students' repairs again beside the 1 passing program of the class"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("the class's programs repaired 2 of 3"), std::string::npos) << run.output;
  const auto before = half_vector.substr(0, half_vector.find("vec3 reflectDir"));
  const std::string line = std::to_string(std::count(before.begin(), before.end(), '\n') + 1);
  const std::string ben = read_text(path("grades/students/ben/results.json"));
  EXPECT_NE(ben.find("phong_frag.js line " + line + ": `reflectDir`, the direction to the light reflected about the normal, is not computed as "
                     "the homework computes it"), std::string::npos) << ben;
  EXPECT_EQ(ben.find("reflect(-lightDir, norm)"), std::string::npos) << "ana's line, shown to ben: " << ben;
  const std::string cyd = read_text(path("grades/students/cyd/results.json"));
  EXPECT_NE(cyd.find("line " + line + ": `reflectDir`"), std::string::npos) << cyd;
  // Its other line in the homework's terms: both lines are where a value departs from the
  // reference's (repair/value_probes.h), and their pair is screened first.
  EXPECT_NE(cyd.find("line " + std::to_string(std::stoi(line) - 4) + ": `uAmbientColor` is never added: the homework's colour adds it"),
            std::string::npos)
      << cyd;

  std::map<std::string, std::vector<nlohmann::json>> lines;
  std::istringstream journal(read_text(path("grades/graded.jsonl")));
  for (std::string text; std::getline(journal, text);) {
    nlohmann::json j = nlohmann::json::parse(text);
    lines[j["student"]].push_back(j);
  }
  ASSERT_EQ(lines["ben"].size(), 2u) << "the first pass's line, then the second's";
  EXPECT_TRUE(lines["ben"][0]["unrepaired"].get<bool>());
  EXPECT_FALSE(lines["ben"][0]["withClass"].get<bool>());
  EXPECT_FALSE(lines["ben"][1]["unrepaired"].get<bool>());
  EXPECT_TRUE(lines["ben"][1]["withClass"].get<bool>());
  EXPECT_GT(lines["ben"][1]["screened"].get<int>(), lines["ben"][0]["screened"].get<int>()) << "both passes counted";
  ASSERT_EQ(lines["dee"].size(), 2u);
  EXPECT_TRUE(lines["dee"][1]["withClass"].get<bool>());
  EXPECT_TRUE(lines["dee"][1]["unrepaired"].get<bool>());
  EXPECT_EQ(lines["dee"][1]["renders"], lines["dee"][0]["renders"]) << "nothing to try: not drawn again";
  EXPECT_EQ(lines["dee"][1]["screened"], lines["dee"][0]["screened"]);
  EXPECT_NE(read_text(path("grades/explanations.csv")).find("R computed otherwise,1,ben"), std::string::npos);

  const auto again = run_cli(command);
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_NE(again.output.find("4 of 4 already graded"), std::string::npos) << again.output;
  EXPECT_EQ(again.output.find("searching"), std::string::npos) << "searched beside the class once: " << again.output;
}

// The class's saved frames looked at across the class: two students who hand in the same frames
// (one re-encoded: the same pixels) are both flagged, and so is one who hands in ShadeLab's own
// render of the reference; a student whose frames are their own page's is not.
TEST_F(CliTest, BatchFlagsSharedFramesAndShadeLabsOwnInTheSummary) {
  const auto preset = [](const std::string& f) { return read_text(std::string(SHADELAB_SOURCE_DIR) + "/shaders/" + f); };
  for (const char* who : {"erin", "frank", "grace", "heidi"}) {
    write(std::string("class/") + who + "/shaders/starter_vert.js", preset("normals_vert.js"));
    write(std::string("class/") + who + "/shaders/starter_frag.js", preset("normals_frag.js"));
  }
  const auto save = [&](const std::string& who, const std::string& angles) {
    const auto r = run_cli("render --preset normals --angles " + angles + " --frames-dir " + path("class/" + who + "/images"));
    ASSERT_EQ(r.status, 0) << r.output;
  };
  save("erin", shadelab::testkit::kPageAngles);
  save("grace", "0,20,40,60,80,100,120,140,160");               // ShadeLab's own, at the exact angles
  save("heidi", "0,19.9,39.7,59.8,79.75,99.9,119.8,139.7,159.85");  // her own page's run
  // frank: erin's frames, re-encoded (the same pixels in other PNG bytes)
  for (int k = 0; k < 9; ++k) {
    const std::string name = "/images/hw2_normals_" + std::to_string(k) + ".png";
    auto image = shadelab::image::decode_png(read_text(path("class/erin" + name)));
    ASSERT_TRUE(image.ok());
    auto png = shadelab::image::encode_png(*image, {.compression_level = 9});
    ASSERT_TRUE(png.ok());
    write("class/frank" + name, std::string(png->begin(), png->end()));
  }
  const auto run = run_cli("grade --submissions " + path("class") + " --reference normals --size 64x48 --out " + path("grades"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("3 students flagged for the TA"), std::string::npos) << run.output;
  std::map<std::string, std::string> line_of;
  std::istringstream summary(read_text(path("grades/summary.csv")));
  for (std::string line; std::getline(summary, line);) line_of[line.substr(0, line.find(','))] = line;
  EXPECT_NE(line_of["erin"].find("the same normals frames, pixel for pixel, as frank"), std::string::npos) << line_of["erin"];
  EXPECT_NE(line_of["frank"].find("the same normals frames, pixel for pixel, as erin"), std::string::npos) << line_of["frank"];
  EXPECT_NE(line_of["grace"].find("made by ShadeLab, not saved from the page"), std::string::npos) << line_of["grace"];
  EXPECT_TRUE(line_of["heidi"].ends_with(",")) << "no flags: " << line_of["heidi"];
  EXPECT_NE(line_of["heidi"].find("heidi,1.000000,1.000000,true"), std::string::npos) << line_of["heidi"];
}

// A server that starts beside another on the same port would get half of its connections: the
// kernel splits them between sockets bound with SO_REUSEPORT, as ShadeLab's used to be.
TEST_F(CliTest, ServeOnAPortAnotherServerHoldsExitsWithAMessage) {
  const int other = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  const int one = 1;
  ::setsockopt(other, SOL_SOCKET, SO_REUSEPORT, &one, sizeof one);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof addr;
  ASSERT_EQ(::bind(other, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  ASSERT_EQ(::listen(other, 8), 0);
  ::getsockname(other, reinterpret_cast<sockaddr*>(&addr), &len);
  // `timeout` turns a server that wrongly starts into a failure here, not a hung test.
  const auto run = shadelab::testkit::run_command("timeout 20 " + std::string(SHADELAB_CLI) + " serve --workers 1 --port " +
                                                  std::to_string(ntohs(addr.sin_port)));
  ::close(other);
  EXPECT_NE(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("already in use"), std::string::npos) << run.output;
}

TEST_F(CliTest, SingleGradeWritesJsonAndAHeatmap) {
  const std::string shaders = std::string(SHADELAB_SOURCE_DIR) + "/shaders/";
  const auto run = run_cli("grade --vert " + shaders + "diffuse_vert.js --frag " + shaders + "diffuse_frag.js --reference diffuse " +
                           "--size 64x48 --format gradescope -o " + path("r.json") + " --heatmap " + path("heat.png"));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto r = nlohmann::json::parse(read_text(path("r.json")));
  EXPECT_EQ(r["score"], 1.0);
  EXPECT_EQ(shadelab::testkit::decode(read_bytes(path("heat.png"))).width, 192);
}

// A full disk (/dev/full answers every write with ENOSPC): a clear error and a failing exit, never
// a silent short file; and no half-written file left under an output's real name.
TEST_F(CliTest, AFullDiskIsAnErrorNotASilentShortFile) {
  const auto full = run_cli("render --preset smooth --frames 1 --size 32x24 --grid /dev/full");
  EXPECT_EQ(full.status, 1) << full.output;
  EXPECT_NE(full.output.find("No space left on device"), std::string::npos) << full.output;
  EXPECT_NE(full.output.find("[io_error]"), std::string::npos) << full.output;

  write("scene.json", R"({"objects":[{"mesh":"cube"}],"render":{"width":64,"height":48,"engine":"workbench"}})");
  const auto scene = run_cli("scene " + path("scene.json") + " -o /dev/full");
  EXPECT_NE(scene.status, 0) << scene.output;
  EXPECT_NE(scene.output.find("No space left on device"), std::string::npos) << scene.output;

  const auto ok = run_cli("render --preset smooth --frames 1 --size 32x24 --grid " + path("out/grid.png"));
  EXPECT_EQ(ok.status, 0) << ok.output;
  EXPECT_TRUE(fs::exists(path("out/grid.png")));
  for (const auto& f : fs::directory_iterator(path("out"))) EXPECT_EQ(f.path().filename(), "grid.png") << "a temporary left behind";
}
