#include "road/client_grade.h"

namespace shadelab::road {

namespace {

// The adapter's warnings, then the road's, after the grader's own.
void add_warnings(std::vector<std::string>& report, const std::vector<std::string>& adapter, const std::vector<std::string>& road) {
  report.insert(report.end(), adapter.begin(), adapter.end());
  report.insert(report.end(), road.begin(), road.end());
}

// A request the adapter could not read whole: the submission's grade where the fault is the
// submission's, else the adapter's Error.
Expected<ClientGraded> unread_for_client(const ClientRoad& road, const CodeRequest& request, const Error& unread) {
  auto misread = grade_misread(unread, request.code, request.reference.empty() ? "custom" : request.reference,
                               request.tolerance.max_score.value_or(1.0), road.limits);
  if (!misread) return misread.take_error();
  return ClientGraded{std::move(*misread), {}};
}

Expected<ClientGraded> code_for_client(const ClientRoad& road, const course::Course& c, CodeRequest request, const ClientGrade& grade,
                                       const course::Viewer& viewer) {
  auto built = code_submission(c, std::move(request), viewer, road.limits);
  if (!built) return built.take_error();
  built->submission.spec.reference_store = road.reference_store;
  built->submission.repair = road.repair;
  auto graded = grade_code(road.pool, std::move(built->submission));
  if (!graded) return graded.take_error();
  add_warnings(graded->result.report.warnings, grade.warnings, built->warnings);
  return ClientGraded{std::move(*graded), {}};
}

Expected<ClientGraded> frames_for_client(const ClientRoad& road, const course::Course& c, FramesRequest request, const ClientGrade& grade,
                                         const course::Viewer& viewer) {
  auto built = frames_submission(c, std::move(request));
  if (!built) return built.take_error();
  if (viewer.sees_references()) built->settings.picture = grade::DifferencePicture::full;
  built->settings.reference_store = road.reference_store;
  built->settings.limits = road.limits;
  auto graded = grade_saved_frames(road.pool, c, *built->checkpoint, std::move(built->submission), built->settings);
  if (!graded) return graded.take_error();
  add_warnings(graded->result.frames.warnings, grade.warnings, built->warnings);
  return ClientGraded{std::move(*graded), built->checkpoint->name};
}

}  // namespace

Expected<ClientGraded> grade_for_client(const ClientRoad& road, const course::Course& course, ClientGrade grade,
                                        const course::Viewer& viewer) {
  if (auto* frames = std::get_if<FramesRequest>(&grade.request)) return frames_for_client(road, course, std::move(*frames), grade, viewer);
  auto& code = std::get<CodeRequest>(grade.request);
  if (grade.unread) return unread_for_client(road, code, *grade.unread);
  return code_for_client(road, course, std::move(code), grade, viewer);
}

}  // namespace shadelab::road
