// The JSON body of POST /api/render, /api/compile and /api/grade without the HTTP around it, so
// the fuzzer spends its time in the field checks: from_json_body, then parse_job, parse_grade_job
// or (saved frames) parse_frames_grade and the road's frames_submission, with the service's limits (the selector byte picks the
// route). Invariants: every rejection says why; a job that passes is within the limits and crosses
// the worker wire unchanged; saved frames come out in the deliverable's order, each by its own
// name, and every frame is either handed in or named missing.
#include <string>

#include "fuzz_check.h"
#include "wire_round_trip.h"
#include "course/course_reader.h"
#include "http/api_request.h"
#include "http/grade_request.h"

namespace {

using namespace shadelab;

void check_job(const worker::Job& job, const http::Limits& limits) {
  const auto& r = job.request;
  FUZZ_CHECK(r.width >= 1 && r.width <= limits.render.max_width);
  FUZZ_CHECK(r.height >= 1 && r.height <= limits.render.max_height);
  FUZZ_CHECK(r.frames >= 1 && r.frames <= limits.render.max_frames);
  FUZZ_CHECK(r.vertex.text.size() <= limits.render.max_source_bytes && r.fragment.text.size() <= limits.render.max_source_bytes);
  fuzz::check_job_crosses_the_wire(job);
}

void check_frames(const road::BuiltFrames& g, const course::Course& c) {
  FUZZ_CHECK(g.checkpoint != nullptr);
  FUZZ_CHECK(g.submission.saved.size() + g.submission.missing.size() == static_cast<size_t>(c.frames));
  for (size_t k = 0; k < g.submission.saved.size() && g.submission.missing.empty(); ++k)
    FUZZ_CHECK(g.submission.saved[k].name == c.frame_file(g.checkpoint->prefix, static_cast<int>(k), "png"));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  shadelab::fuzz::InputReader input(data, size);
  const std::uint8_t selector = input.byte();
  auto raw = http::from_json_body(std::string(input.rest()));
  if (!raw) {
    FUZZ_CHECK(!raw.error().message.empty());
    return 0;
  }
  const http::Limits limits;
  if (selector % 4 == 3) {
    auto frames = http::parse_frames_grade(*raw);
    if (!frames) {
      FUZZ_CHECK(!frames.error().message.empty());
      return 0;
    }
    auto built = road::frames_submission(course::builtin_course(), std::move(frames->request));
    if (built) check_frames(*built, course::builtin_course());
    else FUZZ_CHECK(!built.error().message.empty());
    return 0;
  }
  if (selector % 4 == 2) {
    auto grade = http::parse_code_grade(*raw, limits);
    if (!grade) {
      FUZZ_CHECK(!grade.error().message.empty());
      return 0;
    }
    auto built = road::code_submission(course::builtin_course(), std::move(grade->request), course::Viewer{}, limits.render);
    if (!built) FUZZ_CHECK(!built.error().message.empty());
    else if (render::check_sources(built->submission.render.request, limits.render)) check_job(built->submission.render, limits);  // as grade_code sends it
    return 0;
  }
  auto parsed = http::parse_job(*raw, selector % 4 == 0 ? worker::JobKind::render : worker::JobKind::compile, limits, course::builtin_course());
  if (parsed) check_job(parsed->job, limits);
  else FUZZ_CHECK(!parsed.error().message.empty());
  return 0;
}
