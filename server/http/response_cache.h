#pragma once
// Finished render responses, keyed by their strong ETag (a SHA-256 of the canonical job, the mesh
// bytes and the renderer): renders are deterministic, so a repeat is served without a worker.
// Two tiers: a bounded in-memory LRU in this replica, and with a shared store, Redis, where every
// replica finds what any of them rendered. A shared-store failure is a miss: the job runs.
#include <list>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "store/shared_store.h"

namespace shadelab::http {

struct CachedResponse {
  std::string content_type, body;
  std::map<std::string, std::string> headers;
};

class ResponseCache {
 public:
  ResponseCache(size_t max_bytes, store::SharedStore* shared) : max_bytes_(max_bytes), shared_(shared) {}
  std::optional<CachedResponse> get(const std::string& etag);
  void put(const std::string& etag, CachedResponse response);

 private:
  std::optional<CachedResponse> get_local(const std::string& etag);
  void put_local(const std::string& etag, CachedResponse response);

  size_t max_bytes_, bytes_ = 0;
  store::SharedStore* shared_;
  std::mutex mutex_;
  std::list<std::pair<std::string, CachedResponse>> entries_;  // most recent first
};

}  // namespace shadelab::http
