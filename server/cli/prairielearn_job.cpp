#include "cli/prairielearn_job.h"

#include <nlohmann/json.hpp>

#include "cli/grade_runner.h"
#include "cli/submission_files.h"
#include "core/json_reader.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

Error malformed(const std::string& why) { return make_error(ErrorCode::invalid_argument, why); }

Expected<json> read_data(const fs::path& root) {
  const fs::path file = root / "data" / "data.json";
  if (!fs::is_regular_file(file))
    return malformed("the grading job has no data/data.json: PrairieLearn writes it for every job, so this job is not one of its own");
  json data = json::parse(read_text(file), nullptr, /*allow_exceptions=*/false);
  if (data.is_discarded() || !data.is_object()) return malformed("the grading job's data/data.json is not a JSON object");
  return data;
}

// A path inside the job: relative, without "..", so a question's params cannot point the grader
// at the image's own files.
bool inside_job(const fs::path& p) {
  if (p.empty() || p.is_absolute()) return false;
  for (const auto& part : p)
    if (part == "..") return false;
  return true;
}

}  // namespace

Expected<PrairieLearnJob> read_prairielearn_job(const fs::path& root) {
  auto data = read_data(root);
  if (!data) return data.take_error();
  PrairieLearnJob job;
  const json& params = data->contains("params") ? (*data)["params"] : json::object();
  if (params.is_object() && params.contains("shadelab")) {
    std::string error;
    const JsonReader r(params["shadelab"], "params.shadelab", &error, "params.shadelab");
    r.only({"checkpoint", "course", "part"});
    job.checkpoint = r.text("checkpoint", "");
    job.course = r.text("course", "");
    const std::string part = r.text("part", "whole");
    if (!error.empty()) return malformed("the question's " + error);
    const auto named = hand_in_part_named(part);
    if (!named)
      return malformed("the question's params.shadelab.part is '" + part + "': a part is deliverables (the saved frames and code) or images (the Blender half)");
    if (*named != HandInPart::whole && !job.checkpoint.empty())
      return malformed("the question's params.shadelab names both a checkpoint and a part: a checkpoint question grades that checkpoint's code, a part question one part of the hand-in");
    job.part = *named;
    if (!job.course.empty() && !inside_job(job.course))
      return malformed("the question's params.shadelab.course must be a path inside the grading job (such as serverFilesCourse/shadelab/course.json), not " +
                       job.course.string());
  }
  if (!fs::is_directory(root / "student") || submitted_files(root / "student").empty())
    return malformed("no files were submitted: hand in your files and submit again");
  return job;
}

}  // namespace shadelab::cli
