#pragma once
// A worker's reference and mistake renders, kept for the next submission of the same checkpoint
// (a class is graded checkpoint by checkpoint): least recently used out first, within a byte
// budget, so a worker's memory does not grow with the checkpoints and sizes it has seen.
#include <cstddef>
#include <limits>
#include <string>

#include "core/lru_cache.h"
#include "grade/grader.h"

namespace shadelab::grade {

class ReferenceCache {
 public:
  // The built-in course's specular checkpoint at its 512 x 512 keeps 14 sets of 9 frames (the
  // reference and six mistakes, under two lights): ~132 MB. The default holds one checkpoint's
  // sets at that size.
  static constexpr std::size_t kDefaultBytes = 160u << 20;

  explicit ReferenceCache(std::size_t max_bytes = kDefaultBytes) : sets_(std::numeric_limits<std::size_t>::max(), max_bytes) {}

  const SharedFrames* find(const std::string& key) { return sets_.find(key); }  // a hit becomes the newest
  void insert(std::string key, SharedFrames frames);  // a set larger than the budget is not kept
  std::size_t bytes() const { return sets_.bytes(); }

 private:
  LruCache<SharedFrames> sets_;
};

}  // namespace shadelab::grade
