#include "core/json_reader.h"

#include <cmath>
#include <cstdio>

namespace shadelab {

using nlohmann::json;

namespace {

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

bool number_in(const json& v, double lo, double hi) {
  return v.is_number() && std::isfinite(v.get<double>()) && v.get<double>() >= lo && v.get<double>() <= hi;
}

// Where a reader of a missing or mistyped field points: an empty object that stays alive.
const json& empty_object() {
  static const json empty = json::object();
  return empty;
}

}  // namespace

JsonReader::JsonReader(const json& j, std::string path, std::string* error, const std::string& what)
    : j_(j), path_(std::move(path)), error_(error) {
  if (!j_.is_object()) fail(path_.empty() ? what + " must be a JSON object" : path_ + ": expected an object");
}

std::string JsonReader::at(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
std::string JsonReader::element(const std::string& array_path, size_t index) { return array_path + "[" + std::to_string(index) + "]"; }

bool JsonReader::has(const std::string& key) const { return j_.is_object() && j_.contains(key) && !j_.at(key).is_null(); }
const json& JsonReader::get(const std::string& key) const { return j_.at(key); }

void JsonReader::fail_at(const std::string& path, const std::string& message) const {
  if (error_->empty()) *error_ = path.empty() ? message : path + ": " + message;
}
void JsonReader::fail(const std::string& message) const {
  if (error_->empty()) *error_ = message;
}

bool JsonReader::require(const std::string& key) const {
  if (has(key)) return true;
  fail_at(at(key), "missing (required)");
  return false;
}

double JsonReader::number(const std::string& key, double fallback, double lo, double hi) const {
  if (!has(key)) return fallback;
  if (!number_in(get(key), lo, hi)) {
    fail_at(at(key), "expected a number in [" + fmt(lo) + ", " + fmt(hi) + "]");
    return fallback;
  }
  return get(key).get<double>();
}

int JsonReader::integer(const std::string& key, int fallback, int lo, int hi) const {
  if (!has(key)) return fallback;
  const json& v = get(key);
  if (!v.is_number_integer() || v.get<long long>() < lo || v.get<long long>() > hi) {
    fail_at(at(key), "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return fallback;
  }
  return v.get<int>();
}

bool JsonReader::boolean(const std::string& key, bool fallback) const {
  if (!has(key)) return fallback;
  if (!get(key).is_boolean()) {
    fail_at(at(key), "expected true or false");
    return fallback;
  }
  return get(key).get<bool>();
}

std::string JsonReader::text(const std::string& key, const std::string& fallback, const std::set<std::string>& allowed) const {
  if (!has(key)) return fallback;
  const json& v = get(key);
  if (!v.is_string() || (!allowed.empty() && !allowed.count(v.get<std::string>()))) {
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    fail_at(at(key), allowed.empty() ? "expected a string" : "expected one of " + list);
    return fallback;
  }
  return v.get<std::string>();
}

glm::dvec3 JsonReader::vec3(const std::string& key, glm::dvec3 fallback, double lo, double hi, bool scalar_ok) const {
  if (!has(key)) return fallback;
  const json& v = get(key);
  if (scalar_ok && v.is_number()) {
    const double s = number(key, fallback.x, lo, hi);
    return {s, s, s};
  }
  if (!v.is_array() || v.size() != 3) {
    fail_at(at(key), std::string("expected [x, y, z]") + (scalar_ok ? " or a number" : ""));
    return fallback;
  }
  glm::dvec3 out;
  for (int i = 0; i < 3; ++i) {
    if (!number_in(v[i], lo, hi)) {
      fail_at(element(at(key), i), "expected a number in [" + fmt(lo) + ", " + fmt(hi) + "]");
      return fallback;
    }
    out[i] = v[i].get<double>();
  }
  return out;
}

std::vector<double> JsonReader::numbers(const std::string& key, std::vector<double> fallback, size_t min_size, size_t max_size,
                                        double lo, double hi) const {
  if (!has(key)) return fallback;
  const json& v = get(key);
  if (!v.is_array() || v.size() < min_size || v.size() > max_size) {
    const std::string count = min_size == max_size ? std::to_string(min_size) : std::to_string(min_size) + " to " + std::to_string(max_size);
    fail_at(at(key), "expected an array of " + count + " numbers");
    return fallback;
  }
  std::vector<double> out;
  for (size_t i = 0; i < v.size(); ++i) {
    if (!number_in(v[i], lo, hi)) {
      fail_at(element(at(key), i), "expected a number in [" + fmt(lo) + ", " + fmt(hi) + "]");
      return fallback;
    }
    out.push_back(v[i].get<double>());
  }
  return out;
}

std::vector<std::string> JsonReader::texts(const std::string& key, std::vector<std::string> fallback) const {
  if (!has(key)) return fallback;
  const json& v = get(key);
  if (!v.is_array()) {
    fail_at(at(key), "expected an array of strings");
    return fallback;
  }
  std::vector<std::string> out;
  for (size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_string()) {
      fail_at(element(at(key), i), "expected a string");
      return fallback;
    }
    out.push_back(v[i].get<std::string>());
  }
  return out;
}

std::vector<JsonReader> JsonReader::objects(const std::string& key) const {
  std::vector<JsonReader> out;
  if (!has(key)) return out;
  const json& v = get(key);
  if (!v.is_array()) {
    fail_at(at(key), "expected an array");
    return out;
  }
  for (size_t i = 0; i < v.size(); ++i) out.emplace_back(v[i], element(at(key), i), error_);
  return out;
}

JsonReader JsonReader::object(const std::string& key) const {
  return has(key) ? JsonReader(get(key), at(key), error_) : JsonReader(empty_object(), at(key), error_);
}

void JsonReader::only(const std::set<std::string>& known) const {
  if (!j_.is_object()) return;
  for (auto it = j_.begin(); it != j_.end(); ++it)
    if (!known.count(it.key())) fail_at(at(it.key()), "unknown field");
}

}  // namespace shadelab
