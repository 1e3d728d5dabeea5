#include "road/frames_request.h"

#include <filesystem>
#include <set>

#include "core/words.h"
#include "course/submission_files.h"

namespace shadelab::road {

namespace {

// The files in the deliverable's order, those not handed in, and a warning for each of the rest.
void order_frames(const course::Course& course, const course::Checkpoint& checkpoint, std::vector<HandedInFile> files, BuiltFrames& out) {
  std::vector<std::filesystem::path> names;
  for (const auto& f : files) names.emplace_back(std::filesystem::path(f.name).filename());
  const auto found = course::saved_frame_files(course, checkpoint, names);
  out.submission.missing = found.missing(course, checkpoint);
  std::set<std::string> used;
  for (const auto& frame : found.frames) {
    if (!frame) continue;
    for (auto& f : files)
      if (std::filesystem::path(f.name).filename() == *frame && used.insert(frame->string()).second) {
        out.submission.saved.push_back({frame->string(), std::move(f.bytes)});
        break;
      }
  }
  for (const auto& n : names)
    if (!used.count(n.string()))
      out.warnings.push_back(n.string() + " is not one of the " + checkpoint.name + " deliverable's frames (" + course.saved_frame_range(checkpoint) +
                             ") and was not graded");
}

}  // namespace

Expected<BuiltFrames> frames_submission(const course::Course& course, FramesRequest request) {
  if (request.reference.empty())
    return make_error(ErrorCode::invalid_argument,
                      "give 'reference': the deliverable the frames are of (" + and_list(course.checkpoint_names()) + ")");
  auto found = course.checkpoint(request.reference);
  if (!found) return found.take_error();
  BuiltFrames out;
  if (found->alias) out.warnings.push_back(found->alias->note);
  out.checkpoint = found->checkpoint;
  out.settings.mesh = std::move(request.mesh);
  out.settings.max_score = request.max_score.value_or(found->checkpoint->points);
  out.submission.code = std::move(request.code);
  order_frames(course, *found->checkpoint, std::move(request.files), out);
  return out;
}

}  // namespace shadelab::road
