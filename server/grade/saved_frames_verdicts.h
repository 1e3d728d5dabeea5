#pragma once
// What a set of saved frames is told once it is compared (grade/judge_saved_frames.h): the lags
// found in words, where the frames came from, whether they show the reference's shape, whether
// they are what the student's code renders, and the all-or-nothing verdict saved frames get.
#include <vector>

#include "grade/grade_spec.h"
#include "grade/grader.h"
#include "grade/lag_fit.h"
#include "grade/report.h"

namespace shadelab::grade {

// The lowest outline overlap over the frames: under GradeOptions::same_outline the saved frames
// show another shape (another mesh, another camera) than the one rendered, whatever the shading.
double worst_outline_overlap(const SharedFrames& a, const SharedFrames& b);

// The fits in words: the lags found, and what does not fit (a frame behind the window, one that
// looks like another frame). Frames of the second kind fail.
void describe_fits(const std::vector<LagFit>& fits, const LagGrid& grid, const std::vector<SavedFrame>& saved, Report& r);

// Where the frames came from (grade/provenance.h): ShadeLab's own render of the reference at the
// exact angles (the grid's lag-0 frames) loses the test where the course wants frames saved from
// its page, and is flagged where it does not; no lag on any frame otherwise is flagged for the TA.
void judge_provenance(Report& r, const std::vector<const image::Image*>& saved, const SharedFrames& grid_frames, const LagGrid& grid,
                      const std::vector<LagFit>& fits, bool frames_from_page);

// Pass when every frame passes (after the fits' findings). Saved frames score all or nothing; a
// code grade gives a share per passing frame (grader.cpp's assess).
void settle(Report& r);

// The saved frames against the code's frames at the same angles: are they what the code renders?
Report code_match(const SharedFrames& saved, const SharedFrames& code, const SharedFrames& reference, const Report& frames_report,
                  const GradeSpec& spec, const GradeOptions& options);

// A failing set no mistake named, whose outline is not the reference's: another mesh.
void say_if_another_shape(Report& r, const SharedFrames& frames, const SharedFrames& reference, const GradeOptions& options);

}  // namespace shadelab::grade
