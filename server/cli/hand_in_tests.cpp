#include "cli/hand_in_tests.h"

#include "road/deliverable_score.h"
#include "grade/report.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;
using course::DeliverableTest;

HandInTest test_of(const std::string& name, double score, double max_score, bool pass, const std::string& output) {
  return {name, std::nullopt, score, max_score, pass, TestOutcome::judged, {}, output, nullptr, {}, {}};
}

// Nothing to grade: 0 and what was looked for.
HandInTest absent(const std::string& name, double max_score, const std::string& why) {
  HandInTest test = test_of(name, 0, max_score, false, why + "\n");
  test.outcome = TestOutcome::nothing_to_grade;
  return test;
}

// The grader could not grade it: 0 (neither platform has "not graded" for one test), and words
// that put it on the grader, not the student.
HandInTest ungraded(const std::string& name, double max_score, const Error& e) {
  const std::string what = e.message + " [" + std::string(info(e.code).name) + "]";
  HandInTest test = absent(name, max_score, "The autograder could not grade this: " + what + ". This is not a problem with your submission; please tell the course staff.");
  test.outcome = TestOutcome::grader_failed;
  test.grader_error = what;
  return test;
}

// A report as a test worth `max_score` (its pass, not its own scale, decides the score).
HandInTest graded(const std::string& name, const grade::Report& r, double max_score, const std::string& preface = "") {
  HandInTest test = test_of(name, r.pass ? max_score : 0, max_score, r.pass, preface + grade::output_text(r));
  const auto& w = r.grader_work;
  test.extra_data = {{"graderWork", {{"rendered", w.rendered}, {"fromStore", w.from_store}, {"fromMemory", w.from_memory}}}};
  if (!r.flags.empty()) test.extra_data["flags"] = grade::to_json(r)["flags"];
  return test;
}

// A failed test's heat map, kept for the platform to show.
void attach_heatmap(HandInTest& test, const std::string& worker_png, const std::string& name) {
  if (test.pass || worker_png.empty()) return;
  test.heatmap_png = worker_png;
  test.heatmap_name = name;
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

HandInTest frames_test(const course::Course& c, const DeliverableGrades& d, const road::DeliverableScore& score, const std::vector<fs::path>& files) {
  const course::Checkpoint& k = *d.checkpoint;
  const double max = k.max_score(DeliverableTest::frames, d.points);
  std::string name = test_name(k, DeliverableTest::frames);
  if (!d.frames.any() || !d.frames_grade)
    return absent(name, max, "no saved frames: expected " + c.saved_frame_range(k) + ", saved from the page (its Save button names them so) into images/; the submission has these PNGs: " +
                                 pngs_in(files));
  if (d.frames.frames[0]) name += " (" + (d.frames.frames[0]->parent_path() / c.frame_file(k.prefix, 0, "png")).string() + ", ...)";
  if (!*d.frames_grade) return ungraded(name, max, d.frames_grade->error());
  HandInTest test = graded(name, *scored(score, DeliverableTest::frames)->report, max);
  for (const auto& extra : d.frames.extra) test.output += extra.string() + " is not graded: the deliverable is " + c.saved_frame_range(k) + "\n";
  attach_heatmap(test, (**d.frames_grade).result.heatmap_png, k.name + "_frames");
  return test;
}

std::string code_files(const DeliverableGrades& d) { return d.code->first.string() + ", " + d.code->second.filename().string(); }

HandInTest code_test(const course::Course& c, const DeliverableGrades& d, const road::DeliverableScore& score, const std::vector<fs::path>& files) {
  const course::Checkpoint& k = *d.checkpoint;
  const double max = k.max_score(DeliverableTest::code, d.points);
  if (!d.code)
    return absent(test_name(k, DeliverableTest::code), max, "no shaders for this deliverable: expected " + course::wanted_files(c, k) +
                                                                 " in one folder; the submission has " + course::listing(files));
  const std::string name = test_name(k, DeliverableTest::code) + " (" + code_files(d) + ")";
  if (!*d.code_grade) return ungraded(name, max, d.code_grade->error());
  const std::string note = k.applies(DeliverableTest::code) ? "" : "not part of the grade: this deliverable is graded by its saved frames\n";
  HandInTest test = graded(name, *scored(score, DeliverableTest::code)->report, max, note);
  attach_heatmap(test, (**d.code_grade).result.heatmap_png, k.name);
  return test;
}

HandInTest probe_test(const DeliverableGrades& d, const road::DeliverableScore& score) {
  const course::Checkpoint& k = *d.checkpoint;
  const double max = k.max_score(DeliverableTest::probe, d.points);
  std::string rules;
  for (const auto& p : k.probes) rules += "This test draws under another light (" + p.name + ") to check that " + (p.checks.empty() ? "the shading is right" : p.checks) + ".\n";
  const std::string name = test_name(k, DeliverableTest::probe);
  if (!d.code) return absent(name, max, rules + "no shaders for this deliverable");
  if (!*d.code_grade) return ungraded(name, max, d.code_grade->error());
  return graded(name, *scored(score, DeliverableTest::probe)->report, max, rules);
}

HandInTest match_test(const DeliverableGrades& d, const road::DeliverableScore& score) {
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

std::vector<HandInTest> image_tests(const course::Course& c, const Expected<std::vector<grade::ImageCheck>>& checks) {
  std::vector<HandInTest> tests;
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

std::vector<HandInTest> deliverable_tests(const course::Course& c, const DeliverableGrades& d, const std::vector<fs::path>& files) {
  const course::Checkpoint& k = *d.checkpoint;
  const auto* code = d.code_grade && *d.code_grade ? &(**d.code_grade).result.report : nullptr;
  const auto* frames = d.frames_grade && *d.frames_grade ? &(**d.frames_grade).result : nullptr;
  const road::DeliverableScore score = road::score_deliverable(
      k, d.points, {code, frames ? &frames->frames : nullptr, frames && frames->code ? &*frames->code : nullptr});
  std::vector<HandInTest> tests;
  const auto add = [&](DeliverableTest kind, HandInTest test) {
    test.test = kind;
    tests.push_back(std::move(test));
  };
  add(DeliverableTest::frames, frames_test(c, d, score, files));
  if (k.applies(DeliverableTest::code) || d.code) add(DeliverableTest::code, code_test(c, d, score, files));
  if (k.applies(DeliverableTest::probe)) add(DeliverableTest::probe, probe_test(d, score));
  if (k.applies(DeliverableTest::match) || (d.code && d.frames.any())) add(DeliverableTest::match, match_test(d, score));
  return tests;
}

}  // namespace shadelab::cli
