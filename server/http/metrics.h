#pragma once
// Prometheus text-format metrics: request counts and durations per route, phase durations,
// compile failures, worker crashes and timeouts, queue depth, cache hits.
#include <array>
#include <map>
#include <mutex>
#include <regex>
#include <string>
#include <vector>

#include "http/connection_server.h"
#include "worker/pool.h"

namespace shadelab::http {

class Metrics {
 public:
  // A route the server answers, registered before it serves; its pattern is a label of the metrics.
  void known_route(const std::string& method, const std::string& pattern);
  // The label a request is counted under, from a closed set: a known route as "METHOD pattern"
  // (its id groups written {id}), "unknown" for any other /api/ path, "static" for the page's
  // files. A client's path is never a label: 5,000 made-up paths would be 5,000 series.
  std::string route_label(const std::string& method, const std::string& path) const;
  void request(const std::string& route, int status, double seconds);
  void phase(const std::string& phase, double seconds);
  void compile_failure() { std::lock_guard l(mutex_); ++compile_failures_; }
  void driver_refusal() { std::lock_guard l(mutex_); ++driver_refusals_; }
  void cache(bool hit) { std::lock_guard l(mutex_); ++(hit ? cache_hits_ : cache_misses_); }
  std::string render(const worker::PoolStats& pool, bool ready) const;

 private:
  static constexpr std::array<double, 12> kBuckets = {0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5, 10};
  struct Histogram {
    std::array<std::uint64_t, kBuckets.size()> counts{};
    std::uint64_t count = 0;
    double sum = 0;
    void observe(double v);
  };
  struct Route {
    std::string method;
    std::regex pattern;
    std::string label;
  };
  std::vector<Route> routes_;  // written before the server serves, read only after
  mutable std::mutex mutex_;
  std::map<std::pair<std::string, int>, std::uint64_t> requests_;
  std::map<std::string, Histogram> durations_, phases_;
  std::uint64_t compile_failures_ = 0, driver_refusals_ = 0, cache_hits_ = 0, cache_misses_ = 0;
};

// The connection layer's counters: accepted and refused connections, deadlines missed, open and
// waiting.
std::string render_connection_metrics(const ConnectionStats& s);

}  // namespace shadelab::http
