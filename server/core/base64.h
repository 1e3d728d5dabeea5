#pragma once
// Base64 (RFC 4648, with padding, no line breaks) for images inside JSON and HTML, through
// OpenSSL's encoder (libcrypto is linked for SHA-256 already).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace shadelab {

std::string base64_encode(std::string_view bytes);
std::string base64_encode(const std::vector<std::uint8_t>& bytes);

}  // namespace shadelab
