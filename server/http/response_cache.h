#pragma once
// A bounded in-memory LRU of finished render responses, keyed by their strong ETag (a hash of the
// canonical job, the mesh bytes and the renderer): renders are deterministic, so a repeat is
// served without a worker.
#include <list>
#include <map>
#include <mutex>
#include <optional>
#include <string>

namespace shadelab::http {

struct CachedResponse {
  std::string content_type, body;
  std::map<std::string, std::string> headers;
};

class ResponseCache {
 public:
  explicit ResponseCache(size_t max_bytes) : max_bytes_(max_bytes) {}
  std::optional<CachedResponse> get(const std::string& etag);
  void put(const std::string& etag, CachedResponse response);

 private:
  size_t max_bytes_, bytes_ = 0;
  std::mutex mutex_;
  std::list<std::pair<std::string, CachedResponse>> entries_;  // most recent first
};

}  // namespace shadelab::http
