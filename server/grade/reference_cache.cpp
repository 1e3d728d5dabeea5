#include "grade/reference_cache.h"

namespace shadelab::grade {

void ReferenceCache::insert(std::string key, SharedFrames frames) {
  std::size_t size = 0;
  for (const auto& f : frames) size += f->bytes.size();
  // The grade holds these frames anyway; keeping an oversize set would empty the cache for it.
  if (size > sets_.max_bytes()) return;
  sets_.insert(std::move(key), std::move(frames), size);
}

}  // namespace shadelab::grade
