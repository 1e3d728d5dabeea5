#pragma once
// An optional store shared by every replica behind a load balancer: Redis, holding uploaded
// meshes, finished responses and a course's reference renders (grade/reference_store.h) under
// content addresses, so any replica answers any request and no node renders what another has.
// It is a cache, never the only copy of anything a replica needs to give a right answer: each
// replica keeps its own copies too, Redis bounds its memory and evicts (maxmemory, allkeys-lru),
// and an outage degrades to recomputing. After a failed command the store is left alone for
// `retry_after`, so a dead Redis costs one timeout, not one per request.
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/expected.h"

struct redisContext;

namespace shadelab::store {

struct RedisAddress {
  std::string socket_path;  // a Unix socket (Redis on the same machine), else host and port
  std::string host;
  int port = 6379;
  int db = 0;
};
// `redis://HOST[:PORT][/DB]`, `HOST[:PORT]`, or `unix:///PATH/TO/redis.sock`.
Expected<RedisAddress> parse_redis_url(std::string_view url);

struct SharedStoreConfig {
  std::string url;                                   // empty: no shared store
  std::chrono::milliseconds timeout{250};            // to connect, and for each command
  std::chrono::milliseconds retry_after{2000};       // after a failure, before the next try
  std::chrono::seconds time_to_live{7 * 24 * 3600};  // each entry's expiry (Redis also evicts by LRU)
  size_t max_value_bytes = 32u << 20;                // larger values stay local only

  bool operator==(const SharedStoreConfig&) const = default;
};

class SharedStore {
 public:
  static Expected<std::unique_ptr<SharedStore>> open(SharedStoreConfig config);
  ~SharedStore();
  SharedStore(const SharedStore&) = delete;
  SharedStore& operator=(const SharedStore&) = delete;

  // The value under `key`, nullopt when there is none, store_unavailable when Redis cannot answer.
  Expected<std::optional<std::string>> get(const std::string& key);
  // Stores `value` with the configured expiry; store_unavailable when Redis cannot take it.
  Status put(const std::string& key, std::string_view value);

  std::string render_metrics() const;  // Prometheus text
  const std::string& describe() const { return description_; }

 private:
  explicit SharedStore(SharedStoreConfig config, RedisAddress address);
  struct Connection;
  // A connection from the idle list or a new one; an error while Redis is marked down.
  Expected<std::unique_ptr<Connection>> acquire();
  void release(std::unique_ptr<Connection> connection);
  Error failed(const std::string& what);

  SharedStoreConfig config_;
  RedisAddress address_;
  std::string description_;
  mutable std::mutex mutex_;
  std::vector<std::unique_ptr<Connection>> idle_;
  std::chrono::steady_clock::time_point down_until_{};
  std::uint64_t hits_ = 0, misses_ = 0, stores_ = 0, errors_ = 0, skipped_ = 0;
};

}  // namespace shadelab::store
