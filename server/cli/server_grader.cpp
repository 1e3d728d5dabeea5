#include "cli/server_grader.h"

#include <httplib.h>

#include "core/base64.h"

#include <random>
#include <thread>

namespace shadelab::cli {

namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

struct Endpoint {
  std::string scheme_host_port, prefix;
};

Expected<Endpoint> endpoint_of(const std::string& url) {
  const auto scheme_end = url.find("://");
  if (scheme_end == std::string::npos || (url.compare(0, scheme_end, "http") != 0 && url.compare(0, scheme_end, "https") != 0))
    return make_error(ErrorCode::invalid_argument, "--server takes http://HOST[:PORT][/PREFIX]; got '" + url + "'");
  const auto path = url.find('/', scheme_end + 3);
  Endpoint e{url.substr(0, path), path == std::string::npos ? "" : url.substr(path)};
  while (!e.prefix.empty() && e.prefix.back() == '/') e.prefix.pop_back();
  return e;
}

bool retryable(int status) { return status == 408 || status == 429 || status == 502 || status == 503 || status == 504; }

// What the server said went wrong, in its words when it sent problem+json.
std::string problem_detail(const httplib::Response& res) {
  const json p = json::parse(res.body, nullptr, false);
  if (p.is_object() && p.contains("detail") && p["detail"].is_string())
    return p["detail"].get<std::string>() + " (" + p.value("code", "HTTP " + std::to_string(res.status)) + ")";
  return "HTTP " + std::to_string(res.status);
}

std::chrono::milliseconds backoff(int tries, const httplib::Response* res) {
  static thread_local std::mt19937 random(std::random_device{}());
  const double base = std::min(8.0, 0.25 * (1 << std::min(tries - 1, 5)));
  double seconds = base * std::uniform_real_distribution<double>(0.5, 1.0)(random);  // jitter: not every client at once
  if (res && res->has_header("Retry-After")) seconds = std::max(seconds, std::atof(res->get_header_value("Retry-After").c_str()));
  return std::chrono::milliseconds(static_cast<long>(seconds * 1000));
}

}  // namespace

Expected<ServerGrade> grade_on_server(const ServerOptions& o, const json& body) {
  auto endpoint = endpoint_of(o.url);
  if (!endpoint) return endpoint.take_error();
  httplib::Client client(endpoint->scheme_host_port);
  client.set_connection_timeout(std::chrono::seconds(5));
  client.set_read_timeout(o.request_timeout);
  client.set_write_timeout(std::chrono::seconds(30));
  // Each student's results.json is theirs: graded as the course shows a student, whatever the key.
  httplib::Headers headers{{"X-ShadeLab-View", "student"}};
  if (!o.api_key.empty()) headers.emplace("Authorization", "Bearer " + o.api_key);
  const std::string text = body.dump(-1, ' ', false, json::error_handler_t::replace);
  const auto start = Clock::now();
  std::string last;
  for (int tries = 1;; ++tries) {
    auto res = client.Post(endpoint->prefix + "/api/grade", headers, text, "application/json");
    if (res && res->status == 200) {
      auto report = grade::report_from_json(json::parse(res->body, nullptr, false));
      if (!report) return make_error(ErrorCode::io_error, "the server's answer is not a grade report: " + report.error().message);
      return ServerGrade{std::move(*report), std::chrono::duration<double>(Clock::now() - start).count(), tries};
    }
    if (res && !retryable(res->status)) return make_error(ErrorCode::io_error, o.url + " refused the submission: " + problem_detail(*res));
    last = res ? problem_detail(*res) : httplib::to_string(res.error());
    const auto wait = backoff(tries, res ? &res.value() : nullptr);
    if (Clock::now() + wait - start > o.retry_for)
      return make_error(ErrorCode::io_error, o.url + " did not grade a submission within " + std::to_string(o.retry_for.count()) +
                                                 " s (" + std::to_string(tries) + " tries; last: " + last + ")");
    std::this_thread::sleep_for(wait);
  }
}

Expected<std::vector<std::string>> preset_frames_on_server(const ServerOptions& o, const std::string& course, const std::string& preset) {
  auto endpoint = endpoint_of(o.url);
  if (!endpoint) return endpoint.take_error();
  httplib::Client client(endpoint->scheme_host_port);
  client.set_connection_timeout(std::chrono::seconds(5));
  client.set_read_timeout(o.request_timeout);
  httplib::Headers headers;
  if (!o.api_key.empty()) headers.emplace("Authorization", "Bearer " + o.api_key);
  const httplib::Params query = {{"course", course}, {"preset", preset}, {"output", "json"}};
  auto res = client.Get(endpoint->prefix + "/api/render", query, headers);
  if (!res) return make_error(ErrorCode::io_error, o.url + " did not answer: " + httplib::to_string(res.error()));
  if (res->status == 403) return make_error(ErrorCode::reference_private, problem_detail(*res));
  if (res->status != 200) return make_error(ErrorCode::io_error, o.url + " did not draw " + preset + ": " + problem_detail(*res));
  const json body = json::parse(res->body, nullptr, false);
  std::vector<std::string> frames;
  if (body.is_object() && body.contains("images"))
    for (const auto& f : body["images"].value("frames", json::array()))
      if (auto bytes = base64_decode(f.value("data", "")); bytes) frames.push_back(std::move(*bytes));
  if (frames.empty()) return make_error(ErrorCode::io_error, o.url + " answered " + preset + "'s render without its frames");
  return frames;
}

}  // namespace shadelab::cli
