#pragma once
// FNV-1a, 64-bit: content addresses inside one request's life (ETags, cache keys). Not a
// cryptographic hash: collisions are astronomically unlikely by accident; a wrong cache hit would
// need a crafted collision of two 64-bit hashes, which ETags guard against by hashing twice with
// different seeds. Where an id crosses tenants (an uploaded mesh's id is the capability to use
// it), sha256_hex names it instead: one student must not be able to craft bytes that take the id
// of another's file.
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

// SHA-256 as 64 lower-case hex digits (OpenSSL's libcrypto).
std::string sha256_hex(std::string_view bytes);

}  // namespace shadelab
