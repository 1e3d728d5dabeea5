#include "road/hand_in_checks.h"

#include "worker/client.h"
#include "worker/job.h"
#include "worker/result.h"

namespace shadelab::road {

Expected<std::vector<grade::ImageCheck>> check_hand_in_images(worker::WorkerPool& pool, const course::Course& course, const FindFile& find) {
  worker::ImagesJob job;
  std::vector<grade::ImageCheck> checks;
  for (const auto& wanted : course.images) {
    if (!wanted.checked()) continue;
    const std::string* png = find(wanted.file);
    job.images.push_back({wanted.file, wanted.scene, wanted.objects, png ? *png : std::string(), png ? "" : "not in the submission"});
    checks.push_back({wanted.file, wanted.title, wanted.points, {}});
  }
  if (checks.empty()) return checks;
  auto answered = worker::run<worker::ImagesResult>(pool, worker::to_message(job));
  if (!answered) return answered.take_error();
  auto& verdicts = answered->result.verdicts;
  if (verdicts.size() != checks.size())
    return make_error(ErrorCode::worker_protocol, "a render worker judged " + std::to_string(verdicts.size()) + " of " +
                                                      std::to_string(checks.size()) + " images");
  for (size_t i = 0; i < checks.size(); ++i) checks[i].verdict = std::move(verdicts[i]);
  return checks;
}

}  // namespace shadelab::road
