#include "http/request_fields.h"

#include <cmath>

namespace shadelab::http {

using nlohmann::json;

Error bad_request(std::string message) { return make_error(ErrorCode::invalid_argument, std::move(message)); }

Expected<int> integer_field(const json& fields, const char* name, int fallback) {
  if (!fields.contains(name)) return fallback;
  const json& v = fields[name];
  if (!v.is_number() || (v.is_number_float() && std::trunc(v.get<double>()) != v.get<double>()))
    return bad_request(std::string("'") + name + "' must be a whole number; got " + v.dump());
  const double d = v.get<double>();
  if (d < -1e9 || d > 1e9) return bad_request(std::string("'") + name + "' is out of range");
  return static_cast<int>(d);
}

Expected<double> number_field(const json& fields, const char* name, double fallback) {
  if (!fields.contains(name)) return fallback;
  if (!fields[name].is_number()) return bad_request(std::string("'") + name + "' must be a number; got " + fields[name].dump());
  return fields[name].get<double>();
}

Expected<std::string> text_field(const json& fields, const char* name, const std::string& fallback, std::size_t max) {
  if (!fields.contains(name)) return fallback;
  const json& v = fields[name];
  if (!v.is_string()) return bad_request(std::string("'") + name + "' must be a string; got " + v.dump().substr(0, 80));
  if (v.get_ref<const std::string&>().size() > max)
    return make_error(ErrorCode::payload_too_large, std::string("'") + name + "' is more than " + std::to_string(max) + " bytes");
  return v.get<std::string>();
}

}  // namespace shadelab::http
