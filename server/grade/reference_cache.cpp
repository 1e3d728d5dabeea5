#include "grade/reference_cache.h"

namespace shadelab::grade {

namespace {
std::size_t bytes_of(const SharedFrames& frames) {
  std::size_t n = 0;
  for (const auto& f : frames) n += f->bytes.size();
  return n;
}
}  // namespace

const SharedFrames* ReferenceCache::find(const std::string& key) {
  for (auto it = entries_.begin(); it != entries_.end(); ++it)
    if (it->key == key) {
      entries_.splice(entries_.begin(), entries_, it);
      return &entries_.front().frames;
    }
  return nullptr;
}

void ReferenceCache::insert(std::string key, SharedFrames frames) {
  const std::size_t size = bytes_of(frames);
  if (size > max_bytes_) return;
  while (!entries_.empty() && bytes_ + size > max_bytes_) {
    bytes_ -= entries_.back().bytes;
    entries_.pop_back();
  }
  entries_.push_front({std::move(key), std::move(frames), size});
  bytes_ += size;
}

}  // namespace shadelab::grade
