#pragma once
// Grading a submission: the one road every grade takes. POST /api/grade, `shadelab grade`,
// `autograde` (Gradescope), the class batch, the sheet and `course warm` each parse their input
// into a submission, call one function here, and format the report it returns:
//
//   adapter ──► grade_code / grade_saved_frames ──► worker pool ──► worker ──► grade/judge_code.h,
//   (parses,     (builds the jobs, the        (queue, dead-    (dispatches) judge_saved_frames.h
//    formats)     rule below, the retry)       lines, kills)                (renders: grade_renders.h;
//                                                                            grader.h's verdict)
//
// The rule, applied here and nowhere above: what the submission causes (its source refused
// before any driver, a compile error, a hang or crash that the retry confirms, a frame missing,
// unreadable or not a PNG) is its grade, 0 with the reason; what it does not cause (the queue
// full, no worker, the reference not rendering, a mesh name the course does not have) is an
// Error, never a grade.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/expected.h"
#include "course/code_question.h"
#include "course/course.h"
#include "grade/report.h"
#include "road/repair_search.h"
#include "worker/job.h"
#include "worker/pool.h"
#include "worker/result.h"

namespace shadelab::road {

using ShaderPair = course::Program;

// Code to grade: what to draw (the course's job with the student's shaders, or a render a client
// shaped: its size, uniforms, mesh) and what it is graded against (`spec`, its options included).
struct CodeSubmission {
  worker::Job render;      // the request and the mesh; the kind and the spec are set on the road
  std::string mesh_bytes;  // the mesh's bytes, when they travel with the job
  grade::GradeSpec spec;
  render::RenderLimits limits;  // the caller's: its sources are checked against them, once, on the road
  // How much of a failing grade's repair (road/repair_search.h) is said: the course's choice for
  // its students, the repaired line for whoever may see the references.
  repair::RepairShown repair_shown = repair::RepairShown::where;
  grade::VectorWords vector_words;  // the checkpoint's formula's vectors, for a repair's words
  RepairBudget repair;  // 0 candidates: no search
  std::vector<repair::PassingProgram> classmates;  // a class batch's second pass: its passing programs (road/repair_search.h)
};

struct CodeGrade {
  worker::GradeResult result;  // the report, and the heat map when one was drawn
  double seconds = 0;          // in the queue and in the worker
};

Expected<CodeGrade> grade_code(worker::WorkerPool& pool, CodeSubmission submission);

// Whether a second search of `submission` beside its `classmates` has anything to try
// (road::class_offers_edits): a class batch grades a student again only where it has.
bool second_search_has_candidates(const CodeSubmission& submission);

// The renders `grade_code` drew at the grade's own frames for `report`: the program's own (a retry
// is one more), each repair candidate rendered again to confirm it, and the second grade of a
// failing program no search confirmed a repair for; none for a program that drew nothing. A class's
// cost counted, not timed (the batch's last line, bench/class_bench.sh); the candidates screened
// on a small canvas are `report.repair_search->candidates`.
int full_renders(const grade::Report& report);

// A submission its adapter could not read into a CodeSubmission (a source refused while the
// request was parsed): its grade by the same rule, labelled with the checkpoint and points.
Expected<CodeGrade> grade_unreadable(const Error& error, const std::string& checkpoint, double max_score);

// A request whose other fields could not be read (`field_error`): when the student's own sources
// are refused, that is their grade (0 with the reason, labelled `checkpoint` and `max_score` as the
// request named them as far as it could be read); otherwise the field's error.
Expected<CodeGrade> grade_misread(const Error& field_error, const std::optional<ShaderPair>& code, const std::string& checkpoint,
                                  double max_score, const render::RenderLimits& limits);

// A deliverable not handed in at all (no shader pair in a student's folder): 0, saying what was
// looked for.
grade::Report not_handed_in(const std::string& looked_for, const std::string& checkpoint, double max_score);

// A deliverable's saved frames, and the code handed in beside them.
struct FramesSubmission {
  std::vector<grade::SavedFrame> saved;      // in frame order
  std::vector<std::string> missing;   // the deliverable's frames not handed in, by file name
  std::string unreadable;  // a file that could not be read, in words ("hw2_specular_3.png cannot be read"); empty when none
  std::optional<std::pair<shader::ShaderFile, shader::ShaderFile>> code;  // vertex, fragment
};

// Unset facts are the course's (its default mesh); the score is `max_score`, not the checkpoint's points.
struct FramesSettings {
  std::string mesh;
  double max_score = 1;
  grade::ReferenceStorePlaces reference_store;  // grade/reference_store.h; empty: the worker's memory only
  grade::HeatMap heatmap = grade::HeatMap::always;
  // None: the course's picture (a student's); staff's roads set full.
  std::optional<grade::DifferencePicture> picture;
  render::RenderLimits limits;  // the code's, the caller's (the server's over HTTP)
};

struct FramesGrade {
  worker::FramesGradeResult result;  // the frames' report, the code's when there was code, the heat map
  double seconds = 0;
};

// Against the checkpoint's reference at the frames' lags and, with code, against what that code
// renders. Code that cannot be sent, hangs or crashes is the code's grade; the frames are graded
// without it.
Expected<FramesGrade> grade_saved_frames(worker::WorkerPool& pool, const course::Course& course, const course::Checkpoint& checkpoint,
                                   FramesSubmission submission, const FramesSettings& settings);

}  // namespace shadelab::road
