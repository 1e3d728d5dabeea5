#pragma once
// Grading a submission: the one road every grade takes. POST /api/grade, `shadelab grade`,
// `autograde` (Gradescope), the class batch, the sheet and `course warm` each parse their input
// into a submission, call one function here, and format the report it returns:
//
//   adapter ──► grade_code / grade_frames ──► worker pool ──► worker: GradeSession ──► renderer
//   (parses,     (builds the jobs, the        (queue, dead-    (grade_session.h;
//    formats)     rule below, the retry)       lines, kills)    grader.h's verdict)
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
#include "course/course.h"
#include "grade/report.h"
#include "worker/job.h"
#include "worker/pool.h"
#include "worker/result.h"

namespace shadelab::grade {

// Code to grade: what to draw (the course's job with the student's shaders, or a render a client
// shaped: its size, uniforms, mesh) and what it is graded against (`spec`, its options included).
struct CodeSubmission {
  worker::Job render;      // the request and the mesh; the kind and the spec are set on the road
  std::string mesh_bytes;  // the mesh's bytes, when they travel with the job
  GradeSpec spec;
};

struct CodeGrade {
  worker::GradeResult result;  // the report, and the heat map when one was drawn
  double seconds = 0;          // in the queue and in the worker
};

Expected<CodeGrade> grade_code(worker::WorkerPool& pool, CodeSubmission submission);

// A submission its adapter could not read into a CodeSubmission (a source refused while the
// request was parsed): its grade by the same rule, labelled with the checkpoint and points.
Expected<CodeGrade> grade_unreadable(const Error& error, const std::string& checkpoint, double max_score);

// A deliverable not handed in at all (no shader pair in a student's folder): 0, saying what was
// looked for.
Report not_handed_in(const std::string& looked_for, const std::string& checkpoint, double max_score);

// How the course draws a checkpoint's code: one of its meshes (empty: its default), its canvas and
// frames unless a run sets others.
struct CourseRender {
  std::string mesh;
  std::optional<int> width, height, frames;
};

// The course's submission for a pair of shaders: its job (canvas, frames, page setup), its mesh,
// the checkpoint's spec with `options`. An Error for a mesh or a size the course cannot draw.
Expected<CodeSubmission> course_code(const course::Course& course, const course::Checkpoint& checkpoint, const GradeOptions& options,
                                     const CourseRender& render, shader::ShaderFile vertex, shader::ShaderFile fragment);

// A deliverable's saved frames, and the code handed in beside them.
struct FramesSubmission {
  std::vector<SavedFrame> saved;      // in frame order
  std::vector<std::string> missing;   // the deliverable's frames not handed in, by file name
  std::string unreadable;  // a file that could not be read, in words ("hw2_specular_3.png cannot be read"); empty when none
  std::optional<std::pair<shader::ShaderFile, shader::ShaderFile>> code;  // vertex, fragment
};

// Unset facts are the course's (its default mesh); the score is `max_score`, not the checkpoint's points.
struct FramesSettings {
  std::string mesh;
  double max_score = 1;
  ReferenceStorePlaces reference_store;  // grade/reference_store.h; empty: the worker's memory only
  HeatMap heatmap = HeatMap::always;
};

struct FramesGrade {
  worker::FramesGradeResult result;  // the frames' report, the code's when there was code, the heat map
  double seconds = 0;
};

// Against the checkpoint's reference at the frames' lags and, with code, against what that code
// renders. Code that cannot be sent, hangs or crashes is the code's grade; the frames are graded
// without it.
Expected<FramesGrade> grade_frames(worker::WorkerPool& pool, const course::Course& course, const course::Checkpoint& checkpoint,
                                   FramesSubmission submission, const FramesSettings& settings);

}  // namespace shadelab::grade
