#pragma once
// Checks a response against docs/openapi.json (the one the server serves): the status is
// documented for the route, the content type is one the document lists, and a JSON body matches
// its schema (the subset of JSON Schema the document uses: type, required, properties, items,
// enum, $ref, oneOf).
#include <gtest/gtest.h>
#include <httplib.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/embedded_files.h"

namespace shadelab::testkit {

inline const nlohmann::json& openapi() {
  static const nlohmann::json doc = nlohmann::json::parse(*embedded_file("docs/openapi.json"));
  return doc;
}

inline const nlohmann::json& resolve(const nlohmann::json& schema) {
  if (!schema.contains("$ref")) return schema;
  const std::string ref = schema["$ref"];  // "#/components/schemas/Name"
  return openapi()["components"]["schemas"][ref.substr(ref.find_last_of('/') + 1)];
}

inline bool type_matches(const nlohmann::json& value, const std::string& type) {
  if (type == "object") return value.is_object();
  if (type == "array") return value.is_array();
  if (type == "string") return value.is_string();
  if (type == "integer") return value.is_number_integer();
  if (type == "number") return value.is_number();
  if (type == "boolean") return value.is_boolean();
  if (type == "null") return value.is_null();
  return true;
}

// What in `value` does not match the schema, each with where it is; empty when it conforms.
inline void problems(const nlohmann::json& value, const nlohmann::json& raw_schema, const std::string& where, std::vector<std::string>& out) {
  const nlohmann::json& schema = resolve(raw_schema);
  if (schema.contains("oneOf")) {  // at least one alternative must fit (the document's are disjoint by their required fields)
    std::vector<std::string> why;
    for (const auto& alternative : schema["oneOf"]) {
      std::vector<std::string> p;
      problems(value, alternative, where, p);
      if (p.empty()) return;
      why.push_back(p.front());
    }
    std::string all;
    for (const auto& w : why) all += "\n  " + w;
    out.push_back(where + ": matches none of oneOf:" + all);
    return;
  }
  if (schema.contains("type")) {
    const auto& t = schema["type"];
    bool ok = false;
    if (t.is_array()) {
      for (const auto& one : t) ok |= type_matches(value, one);
    } else {
      ok = type_matches(value, t);
    }
    if (!ok) return out.push_back(where + ": " + value.dump().substr(0, 80) + " is not " + t.dump());
  }
  if (schema.contains("enum")) {
    bool found = false;
    for (const auto& e : schema["enum"]) found |= e == value;
    if (!found) out.push_back(where + ": " + value.dump() + " not in " + schema["enum"].dump());
  }
  if (value.is_object()) {
    for (const auto& r : schema.value("required", nlohmann::json::array()))
      if (!value.contains(r.get<std::string>())) out.push_back(where + ": missing required '" + r.get<std::string>() + "'");
    const nlohmann::json properties = schema.value("properties", nlohmann::json::object());  // outlives items()
    for (const auto& [k, sub] : properties.items())
      if (value.contains(k)) problems(value[k], sub, where + "." + k, out);
  }
  if (value.is_array() && schema.contains("items"))
    for (size_t i = 0; i < value.size(); ++i) problems(value[i], schema["items"], where + "[" + std::to_string(i) + "]", out);
}

inline void validate(const nlohmann::json& value, const nlohmann::json& schema, const std::string& where) {
  std::vector<std::string> found;
  problems(value, schema, where, found);
  for (const auto& p : found) ADD_FAILURE() << p;
}

inline void expect_conforms(const httplib::Response& res, const std::string& path, const std::string& method) {
  const auto& op = openapi()["paths"][path][method];
  ASSERT_TRUE(op.is_object()) << method << " " << path << " is not documented";
  const std::string status = std::to_string(res.status);
  ASSERT_TRUE(op["responses"].contains(status)) << method << " " << path << " does not document status " << status;
  const auto& response = op["responses"][status];
  if (!response.contains("content") || res.body.empty()) return;
  std::string type = res.get_header_value("Content-Type");
  type = type.substr(0, type.find(';'));
  ASSERT_TRUE(response["content"].contains(type)) << method << " " << path << " " << status << " does not list " << type;
  if (type.find("json") == std::string::npos) return;
  validate(nlohmann::json::parse(res.body), response["content"][type]["schema"], method + " " + path);
}

}  // namespace shadelab::testkit
