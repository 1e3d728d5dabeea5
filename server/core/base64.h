#pragma once
// Standard base64 (RFC 4648, padded), for binary data inside JSON or HTML (a data: URI).
#include <string>
#include <string_view>

namespace shadelab {

std::string base64_encode(std::string_view bytes);

}  // namespace shadelab
