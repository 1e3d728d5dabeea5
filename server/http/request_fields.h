#pragma once
// The fields of a request (RawRequest::fields: a JSON body's, or a form's parsed). An absent field
// keeps its fallback; a field of the wrong type is a 400 that names it and quotes what came. Every
// route reads its fields through these, so a client meets one wording.
//
// A request of many fields reads them from one table, each field named once with where it goes:
//
//   const RequestFields<road::CodeRequest> kFields = {
//       field("width", &road::CodeRequest::render, &road::RenderShape::width),
//       field("reference", &road::CodeRequest::reference)};
//   if (auto s = read_fields(raw.fields, kFields, request); !s) ...
//
// How a value is read follows from where it goes: a whole number for an int, a number for a
// double, true or false for a bool, a string for a string, the uniforms object for uniforms.
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/expected.h"
#include "render/render_request.h"

namespace shadelab::http {

// A 400: the request itself is wrong (ErrorCode::invalid_argument).
Error bad_request(std::string message);

Expected<int> integer_field(const nlohmann::json& fields, const char* name, int fallback);
Expected<double> number_field(const nlohmann::json& fields, const char* name, double fallback);
// Longer than `max` bytes: payload_too_large.
Expected<std::string> text_field(const nlohmann::json& fields, const char* name, const std::string& fallback,
                                 std::size_t max = std::numeric_limits<std::size_t>::max());

// One field's value, read into where it goes (the kinds above, and the `uniforms` object: GLSL
// name -> number, boolean or array of numbers). An optional is set only when the field is there.
Status read_value(const nlohmann::json& value, std::string_view key, int& to);
Status read_value(const nlohmann::json& value, std::string_view key, double& to);
Status read_value(const nlohmann::json& value, std::string_view key, bool& to);
Status read_value(const nlohmann::json& value, std::string_view key, std::string& to);
Status read_value(const nlohmann::json& value, std::string_view key, std::vector<render::UniformSetting>& to);
template <class T>
Status read_value(const nlohmann::json& value, std::string_view key, std::optional<T>& to) {
  T read{};
  if (auto s = read_value(value, key, read); !s) return s;
  to = std::move(read);
  return Ok{};
}

template <class Out>
struct RequestField {
  std::string_view key;
  std::function<Status(const nlohmann::json& value, Out& out)> read;
};
template <class Out>
using RequestFields = std::vector<RequestField<Out>>;

// The field `key`, read into the member a path of members names (out.*first.*rest...).
template <class Out, class M, class... Path>
RequestField<Out> field(std::string_view key, M Out::*first, Path... rest) {
  return {key, [key, first, rest...](const nlohmann::json& value, Out& out) -> Status {
            return read_value(value, key, ((out.*first) .* ... .* rest));
          }};
}

// Every field of `table` the request holds, in the table's order; the first that is wrong is the
// error.
template <class Out>
Status read_fields(const nlohmann::json& fields, const RequestFields<Out>& table, Out& out) {
  for (const auto& row : table)
    if (auto found = fields.find(row.key); found != fields.end())
      if (auto s = row.read(*found, out); !s) return s;
  return Ok{};
}

}  // namespace shadelab::http
