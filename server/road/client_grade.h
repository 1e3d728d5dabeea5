#pragma once
// A grade as a client asks for it (POST /api/grade): code or saved frames, as the adapter read
// them. One call here goes the whole road: the submission built from the course's facts
// (road/code_request.h, road/frames_request.h), graded by the rule of road/submission.h, every
// warning put in the report. The adapter parses before and formats after; nothing between.
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/expected.h"
#include "course/access.h"
#include "road/code_request.h"
#include "road/frames_request.h"

namespace shadelab::road {

struct ClientGrade {
  std::variant<CodeRequest, FramesRequest> request;
  // A field of a code grade the adapter could not read: the request's error, unless the student's
  // own sources are refused, which is then their grade (labelled with `reference` and `maxScore`
  // as far as they could be read).
  std::optional<Error> unread;
  std::vector<std::string> warnings;  // the adapter's: fields the grade does not read
};

// What the caller lends the road: its workers, its limits on a render, its reference store, its
// repair search's budget.
struct ClientRoad {
  worker::WorkerPool& pool;
  render::RenderLimits limits;
  grade::ReferenceStorePlaces reference_store;
  RepairBudget repair;
};

struct ClientGraded {
  std::variant<CodeGrade, FramesGrade> grade;  // the kind the request was
  std::string deliverable;                     // saved frames: the checkpoint they were graded as
};

Expected<ClientGraded> grade_for_client(const ClientRoad& road, const course::Course& course, ClientGrade grade,
                                        const course::Viewer& viewer);

}  // namespace shadelab::road
