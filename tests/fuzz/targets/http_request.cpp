// A whole HTTP/1.1 request as a client's bytes reach the service: the connection layer's framing
// (frame_request), then httplib's parsing of the head, query string, JSON, urlencoded and
// multipart bodies, then the readers the API's routes call (read_request, parse_job,
// parse_grade_job, read_scene, parse_scene), stopping where a route would hand the job to a worker.
// Invariants: the framing never claims more than it was given; every request gets an HTTP
// response; a job the routes accept crosses the worker wire unchanged.
#include <httplib.h>

#include <string>

#include "fuzz_check.h"
#include "wire_round_trip.h"
#include "http/memory_stream.h"
#include "http/request_framing.h"
#include "http/request_reader.h"
#include "http/grade_request.h"
#include "course/course_reader.h"

namespace {

using namespace shadelab;

void answer(httplib::Response& res, const Status& status) {
  res.status = status ? 200 : http_status(status.error().code);
  FUZZ_CHECK(status || !status.error().message.empty());
}

// httplib's request processing with the service's settings and routes that stop at the worker.
class ParsingServer : public httplib::Server {
 public:
  ParsingServer() {
    set_payload_max_length(limits_.max_body_bytes);
    const auto job_route = [this](worker::JobKind kind) {
      return [this, kind](const httplib::Request& req, httplib::Response& res) { answer(res, parse(req, kind)); };
    };
    Post("/api/render", job_route(worker::JobKind::render));
    Get("/api/render", job_route(worker::JobKind::render));
    Post("/api/compile", job_route(worker::JobKind::compile));
    Post("/api/grade", job_route(worker::JobKind::grade));
    Post("/api/scene", [this](const httplib::Request& req, httplib::Response& res) { answer(res, parse_scene_request(req)); });
  }

  std::string process(std::string request) {
    std::string response;
    const http::IncomingRequest incoming{std::move(request), {"127.0.0.1", 40000}, {"127.0.0.1", 8889}, true};
    http::MemoryStream stream(incoming, response);
    bool close = false;
    process_request(stream, true, close, nullptr);
    return response;
  }

 private:
  Status parse(const httplib::Request& req, worker::JobKind kind) {
    auto raw = http::read_request(req);
    if (!raw) return raw.take_error();
    if (kind == worker::JobKind::grade) {
      auto grade = http::parse_code_grade(*raw, limits_);
      if (!grade) return grade.take_error();
      auto built = road::code_submission(course::builtin_course(), std::move(grade->request), course::Viewer{}, limits_.render);
      if (!built) return built.take_error();
      if (auto sources = render::check_sources(built->submission.render.request, limits_.render); !sources) return sources;  // as grade_code sends it
      fuzz::check_job_crosses_the_wire(built->submission.render);
      return Ok{};
    }
    auto parsed = http::parse_job(*raw, kind, limits_, course::builtin_course());
    if (!parsed) return parsed.take_error();
    fuzz::check_job_crosses_the_wire(parsed->job);
    return Ok{};
  }

  Status parse_scene_request(const httplib::Request& req) {
    auto upload = http::read_scene(req);
    if (!upload) return upload.take_error();
    auto scene = scene::parse_scene(upload->scene, limits_.scene);
    if (!scene) return scene.take_error();
    fuzz::check_scene_crosses_the_wire(*scene);
    return Ok{};
  }

  http::Limits limits_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  static ParsingServer server;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const http::Framed framed = http::frame_request(bytes, {});
  if (framed.state == http::Framed::State::invalid) {
    FUZZ_CHECK(!framed.error.message.empty());
    return 0;
  }
  if (framed.state == http::Framed::State::incomplete) return 0;
  FUZZ_CHECK(framed.head_bytes > 0 && framed.head_bytes <= framed.request_bytes && framed.request_bytes <= size);
  const std::string response = server.process(std::string(bytes.substr(0, framed.request_bytes)));
  FUZZ_CHECK(response.starts_with("HTTP/1.1 "));
  return 0;
}
