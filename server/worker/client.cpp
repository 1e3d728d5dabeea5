#include "worker/client.h"

namespace shadelab::worker {

bool worth_a_second_try(const Error& e) {
  return e.code == ErrorCode::compile_timeout || e.code == ErrorCode::render_timeout || e.code == ErrorCode::worker_lost ||
         e.code == ErrorCode::grader_failed;
}

}  // namespace shadelab::worker
