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
#include "course/access.h"

namespace shadelab::http {

struct ApiKey {
  std::string key;
  std::string name;                 // how metrics and logs name the tenant (never the key)
  double requests_per_minute = 0;   // 0: the server's default rate
  course::Role role = course::Role::student;  // `staff` in the keys file: sees the references
};

struct TenantLimits {
  std::string api_keys_file;        // empty: no keys required
  // With a keys file: a caller that sends no key is a student, rated per address at
  // `keyless_requests_per_minute` (a class behind one campus address shares it; 0: the default
  // rate); a key gives its role, and a key the file does not hold is still refused.
  bool students_without_keys = false;
  double keyless_requests_per_minute = 0;
  double requests_per_minute = 0;   // per key, or per address without keys; 0: no limit
  double burst = 0;                 // requests at once at the default rate (a key with its own rate: in proportion);
                                    // 0: a tenth of a minute's rate, at least 5
  std::vector<std::string> trusted_proxies;  // addresses or CIDR ranges whose X-Forwarded-For is believed
};

// The client a request comes from: its peer's address, or where the peer is a trusted proxy
// (nginx, an ingress controller), the last address in X-Forwarded-For that is not itself a trusted
// proxy. Only what trusted proxies appended is believed: a client can write any X-Forwarded-For,
// but nginx appends the address it saw, so the right-most untrusted entry is the real one.
std::string client_address(const std::string& peer, const std::string& forwarded_for, const std::vector<std::string>& trusted_proxies);
// Whether `address` is in one of `ranges` ("10.0.0.0/8", "127.0.0.1", "fd00::/8").
bool address_in(const std::string& address, const std::vector<std::string>& ranges);
// A malformed range is an invalid_argument naming it.
Status check_address_ranges(const std::vector<std::string>& ranges);

// The keys file: one key per line, `KEY NAME [REQUESTS_PER_MINUTE] [ROLE]` (ROLE: student, the
// default, or staff); `#` starts a comment.
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
  bool keys_required() const { return !keys_.empty() && !limits_.students_without_keys; }
  bool has_keys() const { return !keys_.empty(); }
  // The role of the key `authorization` carries: a known key's, else a student's.
  course::Role role_of(const std::string& authorization) const;
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
  std::uint64_t unauthorized_ = 0, rate_limited_ = 0, keyless_requests_ = 0;
};

}  // namespace shadelab::http
