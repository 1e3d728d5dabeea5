#pragma once
// Who may call the API, and how often. Optional API keys (a file of keys; clients send
// `Authorization: Bearer KEY`) and a token bucket per key, or per client address where there are
// no keys. Probes, metrics and the page's static files are never limited; /api/ routes are.
#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/expected.h"

namespace shadelab::http {

struct ApiKey {
  std::string key;
  std::string name;                 // how metrics and logs name the tenant (never the key)
  double requests_per_minute = 0;   // 0: the server's default rate
};

struct TenantLimits {
  std::string api_keys_file;        // empty: no keys required
  double requests_per_minute = 0;   // per key, or per address without keys; 0: no limit
  double burst = 0;                 // requests at once at the default rate (a key with its own rate: in proportion);
                                    // 0: a tenth of a minute's rate, at least 5
};

// The keys file: one key per line, `KEY NAME [REQUESTS_PER_MINUTE]`; `#` starts a comment.
Expected<std::vector<ApiKey>> read_api_keys(const std::string& path);

class Tenants {
 public:
  Tenants(TenantLimits limits, std::vector<ApiKey> keys);

  struct Verdict {
    std::optional<Error> refused;   // unauthorized or rate_limited
    int retry_after_seconds = 0;    // rate_limited: when the next request will be allowed
  };
  // `authorization` is the request's Authorization header ("" when absent).
  Verdict admit(const std::string& authorization, const std::string& address);
  bool keys_required() const { return !keys_.empty(); }
  std::string render_metrics() const;

 private:
  struct Bucket {
    double tokens = 0;
    std::chrono::steady_clock::time_point refilled;
  };
  // Takes one token; 0 when there was one, else the seconds until there is.
  int take(const std::string& tenant, double per_minute);

  TenantLimits limits_;
  std::unordered_map<std::string, ApiKey> keys_;
  mutable std::mutex mutex_;
  std::unordered_map<std::string, Bucket> buckets_;
  std::map<std::string, std::uint64_t> requests_by_key_;  // key names: bounded by the file
  std::uint64_t unauthorized_ = 0, rate_limited_ = 0;
};

}  // namespace shadelab::http
