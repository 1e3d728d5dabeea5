#pragma once
// FNV-1a, 64-bit: content addresses (mesh ids, ETags, cache keys). Not a cryptographic hash:
// collisions are astronomically unlikely by accident, and nothing here is a security boundary
// (an id names bytes the same client sent; a wrong cache hit would need a crafted collision of
// two 64-bit hashes, which ETags guard against by hashing twice with different seeds).
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace shadelab {

inline constexpr std::uint64_t kFnvOffsetBasis = 1469598103934665603ull;

inline std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t seed = kFnvOffsetBasis) {
  std::uint64_t h = seed;
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  return h;
}

// 16 lower-case hex digits.
inline std::string hex64(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace shadelab
