#include "http/request_fields.h"

#include <cmath>

#include "core/client_json.h"

namespace shadelab::http {

using nlohmann::json;

namespace {

std::string quoted(std::string_view key) { return "'" + std::string(key) + "'"; }

}  // namespace

Error bad_request(std::string message) { return make_error(ErrorCode::invalid_argument, std::move(message)); }

Status read_value(const json& v, std::string_view key, int& to) {
  if (!v.is_number() || (v.is_number_float() && std::trunc(v.get<double>()) != v.get<double>()))
    return bad_request(quoted(key) + " must be a whole number; got " + describe_client_value(v));
  const double d = v.get<double>();
  if (d < -1e9 || d > 1e9) return bad_request(quoted(key) + " is out of range");
  to = static_cast<int>(d);
  return Ok{};
}

Status read_value(const json& v, std::string_view key, double& to) {
  if (!v.is_number()) return bad_request(quoted(key) + " must be a number; got " + describe_client_value(v));
  to = v.get<double>();
  return Ok{};
}

Status read_value(const json& v, std::string_view key, bool& to) {
  if (!v.is_boolean()) return bad_request(quoted(key) + " must be true or false");
  to = v.get<bool>();
  return Ok{};
}

Status read_value(const json& v, std::string_view key, std::string& to) {
  if (!v.is_string()) return bad_request(quoted(key) + " must be a string; got " + describe_client_value(v));
  to = v.get<std::string>();
  return Ok{};
}

Status read_value(const json& u, std::string_view key, std::vector<render::UniformSetting>& to) {
  if (!u.is_object()) return bad_request(quoted(key) + " must be an object of GLSL name -> number, boolean or array of numbers");
  to.clear();
  for (const auto& [name, value] : u.items()) {
    render::UniformSetting s{name, {}};
    const auto append_value = [&](const json& v) -> Status {
      if (v.is_boolean()) s.values.push_back(v.get<bool>() ? 1.0 : 0.0);
      else if (v.is_number()) s.values.push_back(v.get<double>());
      else return bad_request("uniform '" + s.name + "' must be numbers or booleans; got " + describe_client_value(v));
      return Ok{};
    };
    if (value.is_array()) {
      for (const auto& v : value)
        if (auto st = append_value(v); !st) return st.take_error();
    } else if (auto st = append_value(value); !st) {
      return st.take_error();
    }
    to.push_back(std::move(s));
  }
  return Ok{};
}

Expected<int> integer_field(const json& fields, const char* name, int fallback) {
  if (auto s = fields.contains(name) ? read_value(fields[name], name, fallback) : Status(Ok{}); !s) return s.take_error();
  return fallback;
}

Expected<double> number_field(const json& fields, const char* name, double fallback) {
  if (auto s = fields.contains(name) ? read_value(fields[name], name, fallback) : Status(Ok{}); !s) return s.take_error();
  return fallback;
}

Expected<std::string> text_field(const json& fields, const char* name, const std::string& fallback, std::size_t max) {
  std::string out = fallback;
  if (auto s = fields.contains(name) ? read_value(fields[name], name, out) : Status(Ok{}); !s) return s.take_error();
  if (out.size() > max)
    return make_error(ErrorCode::payload_too_large, quoted(name) + " is more than " + std::to_string(max) + " bytes");
  return out;
}

}  // namespace shadelab::http
