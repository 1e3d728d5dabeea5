#include "http/response_cache.h"

#include "worker/protocol.h"

namespace shadelab::http {

namespace {

std::string shared_key(const std::string& etag) { return "shadelab:1:response:" + etag; }

std::string encode(const std::string& etag, const CachedResponse& r) {
  return worker::encode_message({{{"etag", etag}, {"contentType", r.content_type}, {"headers", r.headers}}, r.body});
}

// The response, if `value` is one stored under this very ETag.
std::optional<CachedResponse> decode(const std::string& etag, const std::string& value) {
  auto message = worker::decode_message(value);
  if (!message) return std::nullopt;
  const auto& h = message->header;
  if (worker::header_text(h, "etag") != etag || !h.contains("contentType") || !h["contentType"].is_string()) return std::nullopt;
  CachedResponse r{h["contentType"], std::move(message->payload), {}};
  if (const auto& headers = h.contains("headers") ? h["headers"] : nlohmann::json(); headers.is_object())
    for (const auto& [k, v] : headers.items())
      if (v.is_string()) r.headers[k] = v;
  return r;
}

}  // namespace

std::optional<CachedResponse> ResponseCache::get(const std::string& etag) {
  if (auto local = get_local(etag)) return local;
  if (!shared_) return std::nullopt;
  auto value = shared_->get(shared_key(etag));
  if (!value || !*value) return std::nullopt;
  auto response = decode(etag, **value);
  if (response) put_local(etag, *response);
  return response;
}

void ResponseCache::put(const std::string& etag, CachedResponse response) {
  if (shared_) (void)shared_->put(shared_key(etag), encode(etag, response));
  put_local(etag, std::move(response));
}

std::optional<CachedResponse> ResponseCache::get_local(const std::string& etag) {
  std::lock_guard lock(mutex_);
  for (auto it = entries_.begin(); it != entries_.end(); ++it)
    if (it->first == etag) {
      entries_.splice(entries_.begin(), entries_, it);
      return entries_.front().second;
    }
  return std::nullopt;
}

void ResponseCache::put_local(const std::string& etag, CachedResponse response) {
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
