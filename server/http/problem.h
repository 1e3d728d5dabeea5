#pragma once
// RFC 9457 problem details: every error response is application/problem+json with a stable
// `code`, a `detail` a student understands, and the shader diagnostics when there are any.
#include <string>

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace shadelab::http {

nlohmann::json problem(const Error& error, const std::string& instance);

}  // namespace shadelab::http
