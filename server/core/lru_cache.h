#pragma once
// What a worker keeps between jobs (compiled programs, parsed and uploaded meshes, reference
// renders): least recently used out first, within a count and a byte budget, so a worker's memory
// does not grow with what it has seen. A linear search: these caches hold tens of entries.
#include <cstddef>
#include <list>
#include <string>
#include <utility>

namespace shadelab {

template <class Value>
class LruCache {
 public:
  LruCache(std::size_t max_entries, std::size_t max_bytes) : max_entries_(max_entries), max_bytes_(max_bytes) {}

  // nullptr when absent; a hit becomes the newest entry.
  Value* find(const std::string& key) {
    for (auto it = entries_.begin(); it != entries_.end(); ++it)
      if (it->key == key) {
        entries_.splice(entries_.begin(), entries_, it);
        return &entries_.front().value;
      }
    return nullptr;
  }

  // Evicts the least recently used entries until the new one fits, and keeps the new one even
  // when it alone is over the byte budget: the caller is about to use it. It stays valid until a
  // later insert evicts it.
  Value& insert(std::string key, Value value, std::size_t bytes) {
    while (!entries_.empty() && (entries_.size() >= max_entries_ || bytes_ + bytes > max_bytes_)) {
      bytes_ -= entries_.back().bytes;
      entries_.pop_back();
    }
    entries_.push_front({std::move(key), std::move(value), bytes});
    bytes_ += bytes;
    return entries_.front().value;
  }

  std::size_t size() const { return entries_.size(); }
  std::size_t bytes() const { return bytes_; }
  std::size_t max_bytes() const { return max_bytes_; }

 private:
  struct Entry {
    std::string key;
    Value value;
    std::size_t bytes;
  };
  std::size_t max_entries_, max_bytes_, bytes_ = 0;
  std::list<Entry> entries_;  // newest first
};

}  // namespace shadelab
