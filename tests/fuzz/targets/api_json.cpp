// The JSON body of POST /api/render, /api/compile and /api/grade without the HTTP around it, so
// the fuzzer spends its time in the field checks: from_json_body, then parse_job or
// parse_grade_job with the service's limits (the selector byte picks the route). Invariants: every
// rejection says why; a job that passes is within the limits and crosses the worker wire unchanged.
#include <string>

#include "fuzz_check.h"
#include "wire_round_trip.h"
#include "course/course_reader.h"
#include "http/api_request.h"

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
  if (selector % 3 == 2) {
    auto grade = http::parse_grade_job(std::move(*raw), limits, course::builtin_course());
    if (grade) check_job(grade->parsed.job, limits);
    else FUZZ_CHECK(!grade.error().message.empty());
    return 0;
  }
  auto parsed = http::parse_job(*raw, selector % 3 == 0 ? worker::JobKind::render : worker::JobKind::compile, limits, course::builtin_course());
  if (parsed) check_job(parsed->job, limits);
  else FUZZ_CHECK(!parsed.error().message.empty());
  return 0;
}
