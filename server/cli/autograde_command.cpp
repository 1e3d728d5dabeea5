// shadelab autograde SUBMISSION -o results.json: the grading step of a Gradescope autograder
// (gradescope/run_autograder). It finds the checkpoints a student's submission holds (their HW2
// folder, or the shader modules alone), grades each through render workers, and writes
// Gradescope's results.json: one test per checkpoint, the heat map of a failed one beside it.
//
// | files in the submission               | checkpoint | graded                      |
// |---------------------------------------|------------|-----------------------------|
// | smooth_vert.js + smooth_frag.js       | smooth     | when present                |
// | gouraud_vert.js + gouraud_frag.js, else starter_vert.js + starter_frag.js | gouraud | always (missing: 0, and why) |
// | diffuse_vert.js + diffuse_frag.js     | diffuse    | when present                |
// | specular_vert.js + specular_frag.js, else phong_vert.js + phong_frag.js   | specular | always (missing: 0, and why) |
//
// The homework edits starter_* into Gouraud shading and phong_* into ambient + diffuse + specular,
// and its checklist hands in that code; a student who kept each stage's files names them.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/file_output.h"
#include "cli/grade_runner.h"
#include "core/base64.h"
#include "grade/report.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct AutogradeFlags {
  GradeFlags grade;
  std::string submission, results, heatmaps;
  size_t embed_limit = 400 * 1024;  // heat maps up to this size go into results.json as an image
};

struct Checkpoint {
  std::string name;
  std::optional<std::string> homework_stem;  // the homework's file names for it, if any
  bool required;
};
const Checkpoint kCheckpoints[] = {
    {"smooth", std::nullopt, false}, {"gouraud", "starter", true}, {"diffuse", std::nullopt, false}, {"specular", "phong", true}};

// Every file under the submission, relative, in path order (so the choice between two copies is
// the same each run); macOS archive litter (__MACOSX/, ._name) and links are not the student's.
std::vector<fs::path> submitted_files(const fs::path& root) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec), end; !ec && it != end;
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name == "__MACOSX" || name == "node_modules" || name.starts_with(".")) {
      if (it->is_directory()) it.disable_recursion_pending();
      continue;
    }
    // A symbolic link is not the student's file: starter_vert.js -> /autograder/... would have
    // the grader read, and quote in its diagnostics, a file of the image.
    if (it->is_regular_file() && !it->is_symlink()) files.push_back(fs::relative(it->path(), root));
  }
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    const auto depth = [](const fs::path& p) { return std::distance(p.begin(), p.end()); };
    return std::pair(depth(a), a.string()) < std::pair(depth(b), b.string());
  });
  return files;
}

// The shallowest folder holding STEM_vert.js and STEM_frag.js.
std::optional<std::pair<fs::path, fs::path>> pair_named(const std::vector<fs::path>& files, const std::string& stem) {
  for (const auto& vert : files) {
    if (vert.filename() != stem + "_vert.js") continue;
    const fs::path frag = vert.parent_path() / (stem + "_frag.js");
    if (std::find(files.begin(), files.end(), frag) != files.end()) return std::pair{vert, frag};
  }
  return std::nullopt;
}

std::string listing(const std::vector<fs::path>& files) {
  if (files.empty()) return "nothing";
  std::string out;
  for (size_t i = 0; i < files.size() && i < 20; ++i) out += (i ? ", " : "") + files[i].string();
  return files.size() > 20 ? out + " and " + std::to_string(files.size() - 20) + " more" : out;
}

std::string html_escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      default: out += c;
    }
  }
  return out;
}

// A checkpoint the submission has no files for: 0 points, and what was looked for.
json missing_test(const Checkpoint& c, double max_score, const std::vector<fs::path>& files) {
  const std::string wanted = *c.homework_stem + "_vert.js and " + *c.homework_stem + "_frag.js (or " + c.name + "_vert.js and " +
                             c.name + "_frag.js)";
  return {{"name", "checkpoint: " + c.name}, {"score", 0.0}, {"max_score", max_score}, {"status", "failed"},
          {"visibility", "visible"},
          {"output", "no shaders for this checkpoint: expected " + wanted + " in one folder; the submission has " + listing(files) + "\n"}};
}

// A graded checkpoint as Gradescope's test, with its heat map (written beside results.json, and
// embedded in the output when small enough) when it failed.
json graded_test(const AutogradeFlags& f, const std::string& checkpoint, const std::pair<fs::path, fs::path>& pair, const Graded& graded) {
  json test = grade::to_gradescope(graded.result.report, graded.seconds)["tests"][0];
  test["name"] = "checkpoint: " + checkpoint + " (" + pair.first.string() + ", " + pair.second.filename().string() + ")";
  const std::string& png = graded.result.heatmap_png;
  if (graded.result.report.pass || png.empty() || f.heatmaps.empty()) return test;
  const fs::path file = fs::path(f.heatmaps) / (checkpoint + ".png");
  if (auto written = write_file(file, png); !written) std::cerr << "autograde: " << written.error().message << "\n";
  if (png.size() > f.embed_limit) {
    test["output"] = test["output"].get<std::string>() + "difference heat map: " + file.string() + "\n";
    return test;
  }
  test["output_format"] = "html";
  test["output"] = "<pre>" + html_escape(test["output"].get<std::string>()) +
                   "</pre><p>Where your frames differ from the reference (brighter: further off):</p>"
                   "<img alt=\"difference heat map\" style=\"max-width:100%\" src=\"data:image/png;base64," +
                   base64_encode(png) + "\">";
  return test;
}

// What to grade: each checkpoint the files hold, and each required one (its pair empty if absent).
using Plan = std::vector<std::pair<const Checkpoint*, std::optional<std::pair<fs::path, fs::path>>>>;
Plan plan_checkpoints(const std::vector<fs::path>& files) {
  Plan plan;
  for (const auto& c : kCheckpoints) {
    auto pair = pair_named(files, c.name);
    if (!pair && c.homework_stem) pair = pair_named(files, *c.homework_stem);
    if (pair || c.required) plan.emplace_back(&c, pair);
  }
  return plan;
}

int run_autograde(const AutogradeFlags& f) {
  const std::vector<fs::path> files = submitted_files(f.submission);
  const Plan plan = plan_checkpoints(files);
  const int jobs = static_cast<int>(std::count_if(plan.begin(), plan.end(), [](const auto& p) { return p.second.has_value(); }));
  worker::WorkerPool pool(pool_config(f.grade, std::max(jobs, 1)));
  json tests = json::array();
  double score = 0, seconds = 0;
  int passed = 0;
  for (const auto& [checkpoint, pair] : plan) {
    if (!pair) {
      tests.push_back(missing_test(*checkpoint, f.grade.max_score, files));
      continue;
    }
    GradeFlags flags = f.grade;
    flags.reference = checkpoint->name;
    const Graded graded = grade_one(pool, flags, fs::path(f.submission) / pair->first, fs::path(f.submission) / pair->second);
    tests.push_back(graded_test(f, checkpoint->name, *pair, graded));
    score += graded.result.report.score;
    seconds += graded.seconds;
    passed += graded.result.report.pass ? 1 : 0;
  }
  const std::string summary = std::to_string(passed) + " of " + std::to_string(plan.size()) + " checkpoints match the reference\n";
  const json results = {{"score", score}, {"execution_time", seconds}, {"output", summary}, {"tests", tests}};
  if (auto s = write_file(f.results, results.dump(2) + "\n"); !s) return fail(s.error());
  std::cout << summary;
  return 0;
}

}  // namespace

Command add_autograde_command(CLI::App& app) {
  auto f = std::make_shared<AutogradeFlags>();
  auto* cmd = app.add_subcommand("autograde", "Grade every checkpoint in a student's submission into Gradescope's results.json");
  cmd->add_option("submission", f->submission, "The submission: the student's HW2 folder, or their shader modules alone")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("-o,--results", f->results, "Where results.json goes")->required();
  cmd->add_option("--heatmaps", f->heatmaps, "Folder for the heat map of each failed checkpoint (<checkpoint>.png)");
  cmd->add_option("--max-score", f->grade.max_score, "Points per checkpoint")->capture_default_str();
  cmd->add_option("--timeout-ms", f->grade.timeout_ms, "Compile and render deadline per checkpoint, in CPU time")->capture_default_str();
  cmd->add_flag("--software", f->grade.software, "Force Mesa's software renderer");
  return [f] { return run_autograde(*f); };
}

}  // namespace shadelab::cli
