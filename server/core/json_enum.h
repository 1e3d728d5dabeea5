#pragma once
// An enum on a JSON wire, by the name its to_string gives. Reading a name this build does not
// know throws nlohmann::json::other_error (the message is malformed), never a silent default as
// NLOHMANN_JSON_SERIALIZE_ENUM would give.
#include <initializer_list>
#include <string>

#include <nlohmann/json.hpp>

namespace shadelab {

template <class Enum>
Enum enum_from_json(const nlohmann::json& j, std::initializer_list<Enum> values) {
  const std::string name = j.get<std::string>();
  for (const Enum v : values)
    if (to_string(v) == name) return v;
  throw nlohmann::json::other_error::create(501, "unknown value '" + name + "'", &j);
}

}  // namespace shadelab
