#include "grade/saved_frames_verdicts.h"

#include <algorithm>
#include <cstdio>

#include "core/words.h"
#include "grade/diagnosis.h"
#include "grade/provenance.h"
#include "image/metrics.h"

namespace shadelab::grade {

namespace {

std::string degrees(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string frame_list(const std::vector<int>& frames) {
  std::vector<std::string> numbers;
  for (int k : frames) numbers.push_back(std::to_string(k));
  return and_list(numbers);
}

// How much two frames' outlines overlap: the pixels either covers that both cover.
double outline_overlap(const image::Image& a, const image::Image& b) {
  size_t both = 0, either = 0;
  for (size_t i = 0; i < a.bytes.size(); i += 4) {
    const bool in_a = !is_clear(&a.bytes[i]), in_b = !is_clear(&b.bytes[i]);
    both += in_a && in_b;
    either += in_a || in_b;
  }
  return either == 0 ? 1 : static_cast<double>(both) / static_cast<double>(either);
}

// Whether frames 1 on were drawn at exactly their nominal angles: what a page with a fixed clock gives.
bool without_lag(const std::vector<LagFit>& fits) {
  if (fits.size() < 2) return false;
  for (size_t k = 1; k < fits.size(); ++k)
    if (fits[k].lag_degrees >= 0.005) return false;
  return true;
}

}  // namespace

// The lowest outline overlap over the frames: under GradeOptions::same_outline the saved frames
// show another shape (another mesh, another camera) than the one rendered, whatever the shading.
double worst_outline_overlap(const SharedFrames& a, const SharedFrames& b) {
  double worst = 1;
  for (size_t k = 0; k < a.size(); ++k) worst = std::min(worst, outline_overlap(*a[k], *b[k]));
  return worst;
}

// The fits in words: the lags found, and what does not fit (a frame behind the window, one that
// looks like another frame). Frames of the second kind fail.
void describe_fits(const std::vector<LagFit>& fits, const LagGrid& grid, const std::vector<SavedFrame>& saved, Report& r) {
  double lo = 1e9, hi = -1e9;
  for (size_t k = 0; k < fits.size(); ++k) {
    const LagFit& f = fits[k];
    r.frames[k].lag_degrees = f.lag_degrees;
    if (k > 0) lo = std::min(lo, f.lag_degrees), hi = std::max(hi, f.lag_degrees);
    if (f.beyond_window)
      r.messages.push_back(saved[k].name + " was drawn " + degrees(grid.window) + " degrees or more behind " + degrees(grid.nominal(f.frame)) +
                           " (the window searched): compared at that limit");
    if (f.looks_like) {
      r.frames[k].grade.pass = false;
      if (r.diagnosis.empty()) r.diagnosis = to_string(Diagnosis::frames_out_of_order);
      r.messages.insert(r.messages.begin(), saved[k].name + " shows frame " + std::to_string(*f.looks_like) + "'s rotation (" +
                                                degrees(grid.nominal(*f.looks_like)) + " degrees), not frame " + std::to_string(k) +
                                                "'s (" + degrees(grid.nominal(f.frame)) + "): saved out of order, or twice?");
    }
  }
  if (without_lag(fits))
    r.messages.push_back("frames 1 to " + std::to_string(fits.size() - 1) + " were drawn at their nominal angles (no lag: a fixed clock)");
  else if (fits.size() > 1)
    r.messages.push_back("frames 1 to " + std::to_string(fits.size() - 1) + " were drawn " + degrees(lo) + " to " + degrees(hi) +
                         " degrees behind their nominal angles (the page draws with the previous frame's time), and were compared there");
}

// Where the frames came from (grade/provenance.h): ShadeLab's own render of the reference at the
// exact angles (the grid's lag-0 frames) loses the test where the course wants frames saved from
// its page, and is flagged where it does not; no lag on any frame otherwise is flagged for the TA.
void judge_provenance(Report& r, const std::vector<const image::Image*>& saved, const SharedFrames& grid_frames, const LagGrid& grid,
                      const std::vector<LagFit>& fits, bool frames_from_page) {
  std::vector<const image::Image*> exact;
  for (int k = 0; k < grid.frames; ++k) exact.push_back(grid_frames[grid.index(k, 0)].get());
  if (drawn_by_shadelab(saved, exact)) {
    r.flags.push_back(made_by_shadelab_flag(grid.frames));
    if (frames_from_page) {
      r.pass = false;
      r.score = 0;
      r.diagnosis = to_string(Diagnosis::made_by_shadelab);
      r.messages.insert(r.messages.begin(), save_from_the_page());
    }
  } else if (without_lag(fits)) {
    r.flags.push_back(no_lag_flag(grid.frames));
  }
}

// Pass when every frame passes (after the fits' findings). Saved frames score all or nothing; a
// code grade gives a share per passing frame (grader.cpp's assess).
void settle(Report& r) {
  r.pass = !r.frames.empty();
  for (const auto& f : r.frames) r.pass = r.pass && f.grade.pass;
  r.score = r.pass ? r.max_score : 0;
}

// The saved frames against the code's frames at the same angles: are they what the code renders?
Report code_match(const SharedFrames& saved, const SharedFrames& code, const SharedFrames& reference, const Report& frames_report,
                  const GradeSpec& spec, const GradeOptions& options) {
  Report r{spec.reference_name, false, 0, options.max_score, "", {}, {}, {}, {}};
  std::vector<int> differing;
  int code_matches_reference = 0;
  for (size_t k = 0; k < saved.size(); ++k) {
    GradeResult one = grade::grade({saved[k]}, {}, {code[k]}, {}, options);
    r.frames.push_back({one.frames[0], "homework", frames_report.frames[k].lag_degrees});
    if (!one.pass) differing.push_back(static_cast<int>(k));
    code_matches_reference += grade::grade({code[k]}, {}, {reference[k]}, {}, options).pass;
  }
  settle(r);
  if (differing.empty()) {
    r.messages.push_back("the saved frames are what your code renders, at the angles they were drawn at");
    return r;
  }
  const bool code_right = code_matches_reference == static_cast<int>(saved.size());
  const double outline = worst_outline_overlap(saved, code);
  if (outline < options.same_outline) {
    r.diagnosis = to_string(Diagnosis::frames_of_another_shape);
    r.messages.push_back("the saved frames show another shape than your code renders on this mesh (the outlines overlap by " + percent(outline) +
                         " at worst): saved with another mesh selected on the page?");
  } else if (differing.size() < saved.size()) {
    r.diagnosis = to_string(Diagnosis::edited_frames);
    r.messages.push_back("frame " + frame_list(differing) + (differing.size() == 1 ? " differs" : " differ") +
                         " from what your code renders, the others match: edited, or saved from another run?");
  } else if (code_right) {
    r.diagnosis = to_string(Diagnosis::stale_frames);
    r.messages.push_back("your code renders the reference, but the saved frames are not what it renders: saved from an earlier version of your code?" +
                         (frames_report.messages.empty() ? std::string() : " (the frames: " + frames_report.messages.front() + ")"));
  } else if (frames_report.pass) {
    r.diagnosis = to_string(Diagnosis::frames_not_from_code);
    r.messages.push_back("the saved frames match the reference, but your code renders something else: they were not made by this code");
  } else {
    r.diagnosis = to_string(Diagnosis::frames_not_from_code);
    r.messages.push_back("the saved frames are not what your code renders, and neither matches the reference");
  }
  return r;
}

// A failing set no mistake named, whose outline is not the reference's: another mesh.
void say_if_another_shape(Report& r, const SharedFrames& frames, const SharedFrames& reference, const GradeOptions& options) {
  const double outline = worst_outline_overlap(frames, reference);
  if (outline >= options.same_outline) return;
  r.diagnosis = to_string(Diagnosis::frames_of_another_shape);
  r.messages.insert(r.messages.begin(), "the saved frames show another shape than the reference on this mesh (the outlines overlap by " +
                                            percent(outline) + " at worst): saved with another mesh selected on the page?");
}

}  // namespace shadelab::grade
