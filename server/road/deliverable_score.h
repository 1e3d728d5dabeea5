#pragma once
// A deliverable's score from what was graded of it: its tests (the saved frames, the code under
// the page's light, the code under the hidden lights, the frames against the code), each worth its
// share of the checkpoint's points (course::Checkpoint::max_score), summed. Gradescope shows each
// test; the sheet and `shadelab sheet` show the sum; all three read it here, so one hand-in has one
// score everywhere.
#include <optional>
#include <string>
#include <vector>

#include "course/course.h"
#include "grade/report.h"

namespace shadelab::road {

// What was graded; null where there was nothing of that kind to grade, or the grader could not.
struct DeliverableReports {
  const grade::Report* code = nullptr;    // the code against the reference (the page's light and the probes)
  const grade::Report* frames = nullptr;  // the saved frames against the reference, at their lags
  const grade::Report* match = nullptr;   // the saved frames against what the code renders
};

struct TestScore {
  course::DeliverableTest test;
  double score = 0, max_score = 0;
  std::optional<grade::Report> report;  // the part of a report this test reads; empty: nothing graded
};

struct DeliverableScore {
  double score = 0, max_score = 0;
  std::vector<TestScore> tests;  // frames, code, probe, match: each that applies or was graded

  // "1 / 1: <the first failing test's first message, else the first test's>".
  std::string verdict() const;
};

DeliverableScore score_deliverable(const course::Checkpoint& checkpoint, double points, const DeliverableReports& graded);

}  // namespace shadelab::road
