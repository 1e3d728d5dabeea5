#include "cli/gradescope_tests.h"

#include <iostream>

#include "cli/file_output.h"
#include "core/base64.h"
#include "road/deliverable_score.h"
#include "grade/report.h"
#include "image/encode.h"
#include "image/png_decode.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using course::DeliverableTest;

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

json test_of(const std::string& name, double score, double max_score, bool pass, const std::string& output) {
  return {{"name", name}, {"score", score}, {"max_score", max_score}, {"status", pass ? "passed" : "failed"},
          {"visibility", "visible"}, {"output", output}};
}

// Nothing to grade: 0 and what was looked for.
json absent(const std::string& name, double max_score, const std::string& why) { return test_of(name, 0, max_score, false, why + "\n"); }

// The grader could not grade it: 0 on Gradescope (it has no "not graded"), and words that put it on
// the grader, not the student.
json ungraded(const std::string& name, double max_score, const Error& e) {
  return absent(name, max_score, "The autograder could not grade this: " + e.message + " [" + std::string(info(e.code).name) +
                                     "]. This is not a problem with your submission; please tell the course staff.");
}

// A report as a test worth `max_score` (its pass, not its own scale, decides the score).
json graded(const std::string& name, const grade::Report& r, double max_score, const std::string& preface = "") {
  json test = test_of(name, r.pass ? max_score : 0, max_score, r.pass, preface + grade::output_text(r));
  const auto& w = r.grader_work;
  test["extra_data"] = {{"graderWork", {{"rendered", w.rendered}, {"fromStore", w.from_store}, {"fromMemory", w.from_memory}}}};
  if (!r.flags.empty()) test["extra_data"]["flags"] = grade::to_json(r)["flags"];
  return test;
}

// The heat map deflated as hard as zlib goes (level 9: ~25% smaller than the workers' fast level 1,
// ~0.15 s for the course's 1536 x 1536 grid), for one over the embedding limit: a page's saved
// frames, each a little off its angle, draw a busier map than ShadeLab's own did.
std::string harder(std::string png, size_t limit) {
  if (png.size() <= limit) return png;
  auto image = image::decode_png(png, 8192);
  auto again = image ? image::encode_png(*image, {.compression_level = 9}) : Expected<std::vector<std::uint8_t>>(image.error());
  if (again && again->size() < png.size()) png.assign(again->begin(), again->end());
  return png;
}

// A failed test's heat map written beside results.json as `file`, and embedded when small enough.
void attach_heatmap(json& test, const std::string& worker_png, const std::string& file, const HeatmapOutput& out) {
  if (test["status"] == "passed" || worker_png.empty() || out.folder.empty()) return;
  const std::string png = harder(worker_png, out.embed_limit);
  const fs::path path = fs::path(out.folder) / (file + ".png");
  if (auto written = write_file(path, png); !written) std::cerr << "autograde: " << written.error().message << "\n";
  if (png.size() > out.embed_limit) {
    test["output"] = test["output"].get<std::string>() + "difference heat map: " + path.string() + "\n";
    return;
  }
  test["output_format"] = "html";
  test["output"] = "<pre>" + html_escape(test["output"].get<std::string>()) +
                   "</pre><p>Where your frames differ from the reference (brighter: further off):</p>"
                   "<img alt=\"difference heat map\" style=\"max-width:100%\" src=\"data:image/png;base64," + base64_encode(png) + "\">";
}

std::string frame_range(const course::Course& c, const course::Checkpoint& k) {
  return c.frame_file(k.prefix, 0, "png") + " to " + c.frame_file(k.prefix, c.frames - 1, "png");
}

std::string pngs_in(const std::vector<fs::path>& files) {
  std::vector<fs::path> pngs;
  for (const auto& f : files)
    if (f.extension() == ".png") pngs.push_back(f);
  return course::listing(pngs);
}

// The test's part of the deliverable's score (road/deliverable_score.h), when it was graded.
const road::TestScore* scored(const road::DeliverableScore& score, DeliverableTest test) {
  for (const auto& t : score.tests)
    if (t.test == test && t.report) return &t;
  return nullptr;
}

std::string test_name(const course::Checkpoint& k, DeliverableTest test) { return k.title + ": " + std::string(to_string(test)); }

json frames_test(const course::Course& c, const DeliverableGrades& d, const road::DeliverableScore& score, const std::vector<fs::path>& files,
                 const HeatmapOutput& heatmaps) {
  const course::Checkpoint& k = *d.checkpoint;
  const double max = k.max_score(DeliverableTest::frames, d.points);
  std::string name = test_name(k, DeliverableTest::frames);
  if (!d.frames.any() || !d.frames_grade)
    return absent(name, max, "no saved frames: expected " + frame_range(c, k) + ", saved from the page (its Save button names them so) into images/; the submission has these PNGs: " +
                                 pngs_in(files));
  if (d.frames.frames[0]) name += " (" + (d.frames.frames[0]->parent_path() / c.frame_file(k.prefix, 0, "png")).string() + ", ...)";
  if (!*d.frames_grade) return ungraded(name, max, d.frames_grade->error());
  json test = graded(name, *scored(score, DeliverableTest::frames)->report, max);
  for (const auto& extra : d.frames.extra)
    test["output"] = test["output"].get<std::string>() + extra.string() + " is not graded: the deliverable is " + frame_range(c, k) + "\n";
  attach_heatmap(test, (**d.frames_grade).result.heatmap_png, k.name + "_frames", heatmaps);
  return test;
}

std::string code_files(const DeliverableGrades& d) { return d.code->first.string() + ", " + d.code->second.filename().string(); }

json code_test(const course::Course& c, const DeliverableGrades& d, const road::DeliverableScore& score, const std::vector<fs::path>& files,
               const HeatmapOutput& heatmaps) {
  const course::Checkpoint& k = *d.checkpoint;
  const double max = k.max_score(DeliverableTest::code, d.points);
  if (!d.code)
    return absent(test_name(k, DeliverableTest::code), max, "no shaders for this deliverable: expected " + course::wanted_files(c, k) +
                                                                 " in one folder; the submission has " + course::listing(files));
  const std::string name = test_name(k, DeliverableTest::code) + " (" + code_files(d) + ")";
  if (!*d.code_grade) return ungraded(name, max, d.code_grade->error());
  const std::string note = k.applies(DeliverableTest::code) ? "" : "not part of the grade: this deliverable is graded by its saved frames\n";
  json test = graded(name, *scored(score, DeliverableTest::code)->report, max, note);
  attach_heatmap(test, (**d.code_grade).result.heatmap_png, k.name, heatmaps);
  return test;
}

json probe_test(const DeliverableGrades& d, const road::DeliverableScore& score) {
  const course::Checkpoint& k = *d.checkpoint;
  const double max = k.max_score(DeliverableTest::probe, d.points);
  std::string rules;
  for (const auto& p : k.probes) rules += "This test draws under another light (" + p.name + ") to check that " + (p.checks.empty() ? "the shading is right" : p.checks) + ".\n";
  const std::string name = test_name(k, DeliverableTest::probe);
  if (!d.code) return absent(name, max, rules + "no shaders for this deliverable");
  if (!*d.code_grade) return ungraded(name, max, d.code_grade->error());
  return graded(name, *scored(score, DeliverableTest::probe)->report, max, rules);
}

json match_test(const DeliverableGrades& d, const road::DeliverableScore& score) {
  const course::Checkpoint& k = *d.checkpoint;
  const double max = k.max_score(DeliverableTest::match, d.points);
  const std::string name = test_name(k, DeliverableTest::match);
  if (!d.code) return absent(name, max, "not compared: no shaders for this deliverable");
  if (!d.frames.any() || !d.frames_grade) return absent(name, max, "not compared: no saved frames");
  if (!*d.frames_grade) return ungraded(name, max, d.frames_grade->error());
  const road::TestScore* match = scored(score, DeliverableTest::match);
  if (!match) return absent(name, max, "not compared: the code was not sent with the frames");
  return graded(name, *match->report, max);
}

std::string image_test_name(const std::string& title, const std::string& file) { return title + " (" + file + ")"; }

}  // namespace

std::vector<json> image_tests(const course::Course& c, const Expected<std::vector<grade::ImageCheck>>& checks) {
  std::vector<json> tests;
  for (const auto& image : c.images) {
    if (!image.checked()) continue;
    const std::string name = image_test_name(image.title, image.file);
    if (!checks) {
      tests.push_back(ungraded(name, image.points, checks.error()));
      continue;
    }
    for (const auto& check : *checks)
      if (check.file == image.file) {
        const std::string preface = check.points == 0 ? "not part of the score (0 points): checked for the TA\n" : "";
        tests.push_back(test_of(name, check.score(), check.points, check.verdict.pass, preface + check.text() + "\n"));
      }
  }
  return tests;
}

std::vector<json> deliverable_tests(const course::Course& c, const DeliverableGrades& d, const std::vector<fs::path>& files,
                                    const HeatmapOutput& heatmaps) {
  const course::Checkpoint& k = *d.checkpoint;
  const auto* code = d.code_grade && *d.code_grade ? &(**d.code_grade).result.report : nullptr;
  const auto* frames = d.frames_grade && *d.frames_grade ? &(**d.frames_grade).result : nullptr;
  const road::DeliverableScore score = road::score_deliverable(
      k, d.points, {code, frames ? &frames->frames : nullptr, frames && frames->code ? &*frames->code : nullptr});
  std::vector<json> tests = {frames_test(c, d, score, files, heatmaps)};
  if (k.applies(DeliverableTest::code) || d.code) tests.push_back(code_test(c, d, score, files, heatmaps));
  if (k.applies(DeliverableTest::probe)) tests.push_back(probe_test(d, score));
  if (k.applies(DeliverableTest::match) || (d.code && d.frames.any())) tests.push_back(match_test(d, score));
  return tests;
}

}  // namespace shadelab::cli
