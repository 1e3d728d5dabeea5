#pragma once
// A PrairieLearn external-grading job as PrairieLearn lays it out under its root (/grade in the
// container; docs/deploy.md, "On PrairieLearn"):
//
//   student/             the files the student submitted (an upload keeps their HW2 folder's paths)
//   data/data.json       the question's data; ShadeLab reads params.shadelab
//   serverFilesCourse/   the course's server files the question names (a course profile may live here)
//   tests/               the question's own tests/ folder
//   results/results.json what the grader writes (cli/prairielearn_results.h)
//
// params.shadelab, all optional: {"checkpoint": NAME} grades that checkpoint's code alone (a
// question where the student edits the two shaders); without it, the whole hand-in, test for test
// as Gradescope grades it. {"part": "deliverables" | "images"} grades one part of the hand-in (a
// question per part: PrairieLearn's upload holds 5 MB, a real hand-in is 8.6 MB): every
// deliverable's saved frames and code, or the Blender half's images; not with "checkpoint".
// {"course": PATH} is a course profile inside the job (relative to the root, e.g.
// "serverFilesCourse/shadelab/course.json"); without it, the image's course.
#include <filesystem>
#include <string>

#include "cli/hand_in_grading.h"
#include "core/expected.h"

namespace shadelab::cli {

struct PrairieLearnJob {
  std::string checkpoint;  // empty: the whole hand-in, or its part
  HandInPart part = HandInPart::whole;
  std::filesystem::path course;  // empty: the grader's own course
};

// The job under `root`; invalid_argument with a sentence for PrairieLearn's format_errors when the
// job is malformed (no data.json, not JSON, a params.shadelab of the wrong shape, a course outside
// the job, no student files).
Expected<PrairieLearnJob> read_prairielearn_job(const std::filesystem::path& root);

}  // namespace shadelab::cli
