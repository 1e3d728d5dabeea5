// How long the pool takes to be whole again after each injected fault (docs/reliability.md).
// Starts the service in-process with 2 real workers and SHADELAB_FAULT_INJECTION set, then for
// each phase x action, REPS times: sends a render whose fragment names the fault, and measures
//   answered: from the fault (the worker logs its steady-clock time just before acting) to the
//             client holding the problem+json;
//   whole:    from the fault to /readyz reporting every worker ready again (polled every 1 ms).
//
//   build/bench/fault_bench [REPS=20] [PHASE...]
#include <httplib.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "http/service.h"
#include "support/files.h"
#include "stats.h"

using nlohmann::json;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {
using shadelab::bench::percentile;

double ms_since_fault(long long fault_ns, Clock::time_point t) {
  return (std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count() - fault_ns) / 1e6;
}

// The steady-clock time of the last fault the log holds.
long long last_fault_ns(const fs::path& log) {
  std::istringstream lines(shadelab::testkit::read_text(log));
  std::string line, last;
  while (std::getline(lines, line))
    if (!line.empty()) last = line;
  return std::stoll(last.substr(last.rfind(' ') + 1));
}

}  // namespace

int main(int argc, char** argv) {
  const int reps = argc > 1 ? std::atoi(argv[1]) : 20;
  std::vector<std::string> phases;
  for (int i = 2; i < argc; ++i) phases.push_back(argv[i]);
  if (phases.empty()) phases = {"compile", "render", "readback", "encode"};
  const fs::path log = fs::temp_directory_path() / ("shadelab_fault_bench_" + std::to_string(::getpid()) + ".log");
  ::setenv("SHADELAB_FAULT_INJECTION", log.c_str(), 1);

  shadelab::http::ServiceConfig config;
  config.port = 0;
  config.pool.workers = 2;
  config.pool.executable = SHADELAB_CLI;
  config.pool.memory_limit_bytes = size_t{512} << 20;
  shadelab::http::Service service(config);
  auto port = service.start();
  if (!port) {
    std::fprintf(stderr, "the service did not start: %s\n", port.error().message.c_str());
    return 1;
  }
  httplib::Client client("127.0.0.1", *port);
  client.set_read_timeout(120, 0);
  const auto whole = [&] {
    auto r = client.Get("/readyz");
    const json j = r ? json::parse(r->body, nullptr, false) : json();
    return j.is_object() && j.value("workersReady", 0) == j.value("workers", -1);
  };
  while (!whole()) std::this_thread::sleep_for(std::chrono::milliseconds(10));

  const std::string vertex = shadelab::testkit::read_text(std::string(SHADELAB_SOURCE_DIR) + "/shaders/specular_vert.js");
  const std::string fragment = shadelab::testkit::read_text(std::string(SHADELAB_SOURCE_DIR) + "/shaders/specular_frag.js");
  std::printf("%-9s %-9s %4s  %-24s %-24s %s\n", "phase", "action", "n", "answered ms p50/p99/max", "whole ms p50/p99/max", "answer");
  int serial = 0;
  for (const auto& phase : phases)
    for (const std::string action : {"kill", "crash", "truncate", "stop", "close", "garbage", "noise", "hog"}) {
      std::vector<double> answered, recovered;
      std::string code;
      for (int i = 0; i < reps; ++i) {
        const json job = {{"vertex", vertex}, {"fragment", fragment + "\n// shadelab-fault: " + phase + " " + action + " " + std::to_string(++serial) + "\n"},
                          {"width", 64}, {"height", 48}, {"frames", 3}};
        auto r = client.Post("/api/render", job.dump(), "application/json");
        const auto answered_at = Clock::now();
        while (!whole()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        const auto whole_at = Clock::now();
        const long long fault = last_fault_ns(log);
        answered.push_back(ms_since_fault(fault, answered_at));
        recovered.push_back(ms_since_fault(fault, whole_at));
        code = r ? std::to_string(r->status) + " " + json::parse(r->body, nullptr, false).value("code", "") : "no answer";
      }
      char a[64], w[64];
      std::snprintf(a, sizeof a, "%.0f / %.0f / %.0f", percentile(answered, 0.5), percentile(answered, 0.99), percentile(answered, 1));
      std::snprintf(w, sizeof w, "%.0f / %.0f / %.0f", percentile(recovered, 0.5), percentile(recovered, 0.99), percentile(recovered, 1));
      std::printf("%-9s %-9s %4d  %-24s %-24s %s\n", phase.c_str(), action.c_str(), reps, a, w, code.c_str());
      std::fflush(stdout);
    }
  service.stop();
  fs::remove(log);
  return 0;
}
