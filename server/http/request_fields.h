#pragma once
// The fields of a request (RawRequest::fields: a JSON body's, or a form's parsed), read one at a
// time: an absent field is the fallback; a field of the wrong type is a 400 that names it and
// quotes what came. Every route reads its fields through these, so a client meets one wording.
#include <cstddef>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/expected.h"

namespace shadelab::http {

// A 400: the request itself is wrong (ErrorCode::invalid_argument).
Error bad_request(std::string message);

Expected<int> integer_field(const nlohmann::json& fields, const char* name, int fallback);
Expected<double> number_field(const nlohmann::json& fields, const char* name, double fallback);
// Longer than `max` bytes: payload_too_large.
Expected<std::string> text_field(const nlohmann::json& fields, const char* name, const std::string& fallback,
                                 std::size_t max = std::numeric_limits<std::size_t>::max());

}  // namespace shadelab::http
