#pragma once
// Base64 (RFC 4648, with padding, no line breaks) for images inside JSON and HTML, through
// OpenSSL's encoder and decoder (libcrypto is linked for SHA-256 already).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace shadelab {

std::string base64_encode(std::string_view bytes);
std::string base64_encode(const std::vector<std::uint8_t>& bytes);
// The bytes `text` encodes (padded, no whitespace), or nullopt when it is not base64.
std::optional<std::string> base64_decode(std::string_view text);

}  // namespace shadelab
