#include "http/response_cache.h"

namespace shadelab::http {

std::optional<CachedResponse> ResponseCache::get(const std::string& etag) {
  std::lock_guard lock(mutex_);
  for (auto it = entries_.begin(); it != entries_.end(); ++it)
    if (it->first == etag) {
      entries_.splice(entries_.begin(), entries_, it);
      return entries_.front().second;
    }
  return std::nullopt;
}

void ResponseCache::put(const std::string& etag, CachedResponse response) {
  const size_t size = response.body.size();
  if (size > max_bytes_ / 4) return;  // one huge response must not flush everything else
  std::lock_guard lock(mutex_);
  for (const auto& e : entries_)
    if (e.first == etag) return;
  entries_.emplace_front(etag, std::move(response));
  bytes_ += size;
  while (bytes_ > max_bytes_ && !entries_.empty()) {
    bytes_ -= entries_.back().second.body.size();
    entries_.pop_back();
  }
}

}  // namespace shadelab::http
