// The process boundary read from the untrusted side: a message as decode_message reads a value
// from the shared store (Redis), then every reader of it: the worker's job readers and the HTTP
// process's readers of a worker's answer (a worker runs student code; its answer is not trusted).
// Invariants: nothing thrown; a decoded message encodes back to one that decodes equal; a job
// read from a message re-encodes to a message that reads as the same job; an answer that reads
// as a result answers again as the same message.
#include <string>

#include "fuzz_check.h"
#include "wire_round_trip.h"
#include "worker/job.h"
#include "worker/result.h"

namespace {

using shadelab::worker::Message;

void check_job(const Message& m) {
  auto job = shadelab::worker::job_from_message(m);
  if (!job) return;
  const Message again = shadelab::worker::to_message(*job, m.payload);
  auto reread = shadelab::worker::job_from_message(again);
  FUZZ_CHECK(reread.ok());
  FUZZ_CHECK(shadelab::fuzz::same_message(shadelab::worker::to_message(*reread, m.payload), again));
}

void check_scene_job(const Message& m) {
  auto job = shadelab::worker::scene_job_from_message(m);
  if (!job) return;
  const Message again = shadelab::worker::to_message(*job);
  auto reread = shadelab::worker::scene_job_from_message(again);
  FUZZ_CHECK(reread.ok());
  FUZZ_CHECK(shadelab::fuzz::same_message(shadelab::worker::to_message(*reread), again));
}

template <class Result>
void check_answer(const Message& m) {
  auto result = shadelab::worker::result_from<Result>(m);
  if (!result) {
    FUZZ_CHECK(!result.error().message.empty());
    return;
  }
  const Message again = shadelab::worker::answer(*result);
  auto reread = shadelab::worker::result_from<Result>(again);
  FUZZ_CHECK(reread.ok());
  FUZZ_CHECK(shadelab::fuzz::same_message(shadelab::worker::answer(*reread), again));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  auto decoded = shadelab::worker::decode_message(bytes);
  if (!decoded) return 0;
  auto round_trip = shadelab::worker::decode_message(shadelab::worker::encode_message(*decoded));
  FUZZ_CHECK(round_trip.ok() && shadelab::fuzz::same_message(*round_trip, *decoded));
  (void)shadelab::worker::job_kind_of(*decoded);
  check_job(*decoded);
  check_scene_job(*decoded);
  using namespace shadelab::worker;
  check_answer<CompileResult>(*decoded);
  check_answer<RenderResult>(*decoded);
  check_answer<MeshCheckResult>(*decoded);
  check_answer<SceneResult>(*decoded);
  check_answer<GradeResult>(*decoded);
  return 0;
}
