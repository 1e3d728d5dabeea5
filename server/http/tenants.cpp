#include "http/tenants.h"

#include <arpa/inet.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace shadelab::http {

namespace {

using Clock = std::chrono::steady_clock;
constexpr size_t kMaxBuckets = 100'000;  // addresses remembered at once; full buckets go first

std::string bearer_token(const std::string& authorization) {
  constexpr std::string_view kScheme = "Bearer ";
  if (authorization.size() <= kScheme.size()) return "";
  if (!std::equal(kScheme.begin(), kScheme.end(), authorization.begin(),
                  [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b)); }))
    return "";
  return authorization.substr(kScheme.size());
}

// What follows a key's name: its rate (a number), then its role, each optional.
bool key_options(std::istringstream& fields, ApiKey& k) {
  std::string word;
  if (!(fields >> word)) return true;
  if (std::isdigit(static_cast<unsigned char>(word[0])) || word[0] == '.') {
    std::istringstream rate(word);
    if (!(rate >> k.requests_per_minute) || !rate.eof() || k.requests_per_minute < 0) return false;
    if (!(fields >> word)) return true;
  }
  const auto role = course::role_named(word);
  if (!role) return false;
  k.role = *role;
  return !(fields >> word);
}

}  // namespace

Expected<std::vector<ApiKey>> read_api_keys(const std::string& path) {
  std::ifstream in(path);
  if (!in) return make_error(ErrorCode::io_error, "cannot read the API keys file '" + path + "'");
  std::vector<ApiKey> keys;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    line = line.substr(0, line.find('#'));
    std::istringstream fields(line);
    ApiKey k;
    if (!(fields >> k.key)) continue;
    if (!(fields >> k.name) || !key_options(fields, k))
      return make_error(ErrorCode::invalid_argument, path + ":" + std::to_string(number) + ": expected KEY NAME [REQUESTS_PER_MINUTE] [student|staff]");
    if (!std::all_of(k.name.begin(), k.name.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'; }))
      return make_error(ErrorCode::invalid_argument, path + ":" + std::to_string(number) + ": a name may hold letters, digits, '_', '-' and '.'");
    if (k.key.size() < 16)
      return make_error(ErrorCode::invalid_argument, path + ":" + std::to_string(number) + ": a key must have at least 16 characters");
    keys.push_back(std::move(k));
  }
  if (keys.empty()) return make_error(ErrorCode::invalid_argument, "the API keys file '" + path + "' holds no keys");
  return keys;
}

Tenants::Tenants(TenantLimits limits, std::vector<ApiKey> keys) : limits_(std::move(limits)) {
  for (auto& k : keys) keys_.emplace(k.key, std::move(k));
}

Tenants::Verdict Tenants::admit(const std::string& authorization, const std::string& address) {
  std::string tenant = "address " + address;
  double rate = limits_.requests_per_minute;
  const bool keyless_student = !keys_.empty() && limits_.students_without_keys && authorization.empty();
  if (keyless_student) {
    tenant = "keyless " + address;
    if (limits_.keyless_requests_per_minute > 0) rate = limits_.keyless_requests_per_minute;
    std::lock_guard lock(mutex_);
    ++keyless_requests_;
  } else if (!keys_.empty()) {
    const auto key = keys_.find(bearer_token(authorization));
    if (key == keys_.end()) {
      std::lock_guard lock(mutex_);
      ++unauthorized_;
      return {make_error(ErrorCode::unauthorized, authorization.empty() ? "send an API key: Authorization: Bearer KEY"
                                                                        : "that API key is not known to this server"),
              0};
    }
    tenant = "key " + key->second.name;
    if (key->second.requests_per_minute > 0) rate = key->second.requests_per_minute;
    std::lock_guard lock(mutex_);
    ++requests_by_key_[key->second.name];
  }
  if (rate <= 0) return {};
  const int wait = take(tenant, rate);
  if (wait == 0) return {};
  return {make_error(ErrorCode::rate_limited, "over " + std::to_string(static_cast<long>(rate)) + " requests a minute for this " +
                                                  (keys_.empty() || keyless_student ? "address" : "key") + "; retry in " + std::to_string(wait) + " s"),
          wait};
}

course::Role Tenants::role_of(const std::string& authorization) const {
  const auto key = keys_.find(bearer_token(authorization));
  return key == keys_.end() ? course::Role::student : key->second.role;
}

int Tenants::take(const std::string& tenant, double per_minute) {
  // --burst is for the default rate; a key with a rate of its own gets a burst in proportion.
  const double base = limits_.requests_per_minute > 0 ? limits_.requests_per_minute : per_minute;
  const double burst = limits_.burst > 0 ? limits_.burst * per_minute / base : std::max(5.0, per_minute / 10);
  const double per_second = per_minute / 60;
  const auto now = Clock::now();
  std::lock_guard lock(mutex_);
  if (buckets_.size() >= kMaxBuckets)
    std::erase_if(buckets_, [&](const auto& entry) {
      return entry.second.tokens + per_second * std::chrono::duration<double>(now - entry.second.refilled).count() >= burst;
    });
  Bucket& b = buckets_.try_emplace(tenant, Bucket{burst, now}).first->second;
  b.tokens = std::min(burst, b.tokens + per_second * std::chrono::duration<double>(now - b.refilled).count());
  b.refilled = now;
  if (b.tokens >= 1) {
    b.tokens -= 1;
    return 0;
  }
  ++rate_limited_;
  return std::max(1, static_cast<int>(std::ceil((1 - b.tokens) / per_second)));
}

std::string Tenants::render_metrics() const {
  std::lock_guard lock(mutex_);
  std::ostringstream out;
  out << "# TYPE shadelab_unauthorized_total counter\nshadelab_unauthorized_total " << unauthorized_ << "\n"
      << "# TYPE shadelab_rate_limited_total counter\nshadelab_rate_limited_total " << rate_limited_ << "\n"
      << "# TYPE shadelab_keyless_requests_total counter\nshadelab_keyless_requests_total " << keyless_requests_ << "\n"
      << "# TYPE shadelab_key_requests_total counter\n";
  for (const auto& [name, n] : requests_by_key_) out << "shadelab_key_requests_total{key=\"" << name << "\"} " << n << "\n";
  return out.str();
}

}  // namespace shadelab::http

namespace shadelab::http {

namespace {

// An address as bytes (4 for IPv4, 16 for IPv6); empty when it is neither.
std::string address_bytes(const std::string& text) {
  unsigned char buf[16];
  if (inet_pton(AF_INET, text.c_str(), buf) == 1) return std::string(reinterpret_cast<char*>(buf), 4);
  if (inet_pton(AF_INET6, text.c_str(), buf) == 1) return std::string(reinterpret_cast<char*>(buf), 16);
  return "";
}

struct Range {
  std::string network;
  int prefix_bits = 0;
};

std::optional<Range> parse_range(const std::string& text) {
  const auto slash = text.find('/');
  Range r{address_bytes(text.substr(0, slash)), 0};
  if (r.network.empty()) return std::nullopt;
  const int max_bits = static_cast<int>(r.network.size()) * 8;
  r.prefix_bits = max_bits;
  if (slash != std::string::npos) {
    const std::string bits = text.substr(slash + 1);
    if (bits.empty() || bits.size() > 3 || !std::all_of(bits.begin(), bits.end(), [](char c) { return c >= '0' && c <= '9'; })) return std::nullopt;
    r.prefix_bits = std::stoi(bits);
    if (r.prefix_bits > max_bits) return std::nullopt;
  }
  return r;
}

bool in_range(const std::string& address, const Range& r) {
  if (address.size() != r.network.size()) return false;
  for (int bit = 0; bit < r.prefix_bits; ++bit) {
    const int mask = 0x80 >> (bit % 8);
    if ((address[bit / 8] & mask) != (r.network[bit / 8] & mask)) return false;
  }
  return true;
}

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

}  // namespace

bool address_in(const std::string& address, const std::vector<std::string>& ranges) {
  const std::string bytes = address_bytes(address);
  if (bytes.empty()) return false;
  for (const auto& text : ranges)
    if (const auto r = parse_range(text); r && in_range(bytes, *r)) return true;
  return false;
}

Status check_address_ranges(const std::vector<std::string>& ranges) {
  for (const auto& r : ranges)
    if (!parse_range(r)) return make_error(ErrorCode::invalid_argument, "--trusted-proxy takes an address or a CIDR range; got '" + r + "'");
  return Ok{};
}

std::string client_address(const std::string& peer, const std::string& forwarded_for, const std::vector<std::string>& trusted_proxies) {
  if (trusted_proxies.empty() || !address_in(peer, trusted_proxies)) return peer;
  std::string client = peer;
  size_t end = forwarded_for.size();
  while (end > 0) {
    const size_t comma = forwarded_for.rfind(',', end - 1);
    const size_t begin = comma == std::string::npos ? 0 : comma + 1;
    const std::string hop = trim(forwarded_for.substr(begin, end - begin));
    if (address_bytes(hop).empty()) break;  // not an address: stop believing the chain here
    client = hop;
    if (!address_in(hop, trusted_proxies)) break;
    if (comma == std::string::npos) break;
    end = comma;
  }
  return client;
}

}  // namespace shadelab::http
