#pragma once
// Grades a submission through a ShadeLab server (one server, or nginx in front of replicas), as
// `shadelab grade --server URL` does: POST /api/grade, retried while the service is busy or a
// replica is going away, until `retry_for` has passed.
//
// | answer                                   | what the client does                               |
// |------------------------------------------|----------------------------------------------------|
// | 200 with a report                        | the grade                                          |
// | 408, 429, 502, 503, 504, connection error| waits (Retry-After, else backoff 0.25 s doubling to 8 s, jittered), sends again |
// | any other status                         | stops the batch with the server's problem detail   |
#include <chrono>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/expected.h"
#include "grade/report.h"

namespace shadelab::cli {

struct ServerOptions {
  std::string url;                            // http://HOST[:PORT][/PREFIX]
  std::string api_key;                        // sent as Authorization: Bearer KEY when not empty
  std::chrono::seconds retry_for{300};        // per submission, then the batch stops
  std::chrono::seconds request_timeout{120};  // one request's read deadline
};

struct ServerGrade {
  grade::Report report;
  double seconds = 0;  // from the first try to the answer
  int tries = 1;
};

// `body`: the POST /api/grade JSON request.
Expected<ServerGrade> grade_on_server(const ServerOptions& options, const nlohmann::json& body);

// The frames (PNG bytes) of the course's job the server draws for `preset` at the exact angles:
// GET /api/render?output=json. A reference needs a staff key: reference_private without one.
Expected<std::vector<std::string>> preset_frames_on_server(const ServerOptions& options, const std::string& course, const std::string& preset);

}  // namespace shadelab::cli
