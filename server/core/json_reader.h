#pragma once
// Reads fields off one JSON object of a document a person wrote (a scene, a course profile),
// keeping the first problem with its path ("checkpoints[2].prefix: expected a string") and
// carrying on with defaults, so a parser reads straight through without an error check per field.
// One shape for every such document: the path names the field, the text says what was expected.
#include <set>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace shadelab {

class JsonReader {
 public:
  // `what` names the document in the message when the root is not an object ("the scene").
  JsonReader(const nlohmann::json& j, std::string path, std::string* error, const std::string& what = "the document");

  // The path of a field of this object, and of an element of an array field.
  std::string at(const std::string& key) const;
  static std::string element(const std::string& array_path, size_t index);

  bool has(const std::string& key) const;
  const nlohmann::json& get(const std::string& key) const;
  // Records "PATH: MESSAGE" unless a problem is recorded already.
  void fail_at(const std::string& path, const std::string& message) const;
  void fail(const std::string& message) const;
  // A field the format cannot do without: false, and the problem recorded, when it is absent.
  bool require(const std::string& key) const;

  double number(const std::string& key, double fallback, double lo, double hi) const;
  int integer(const std::string& key, int fallback, int lo, int hi) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string text(const std::string& key, const std::string& fallback, const std::set<std::string>& allowed = {}) const;
  // [x, y, z]; `scalar_ok` also takes one number for all three (scale).
  glm::dvec3 vec3(const std::string& key, glm::dvec3 fallback, double lo, double hi, bool scalar_ok = false) const;
  // An array of numbers with a length in [min_size, max_size], each in [lo, hi].
  std::vector<double> numbers(const std::string& key, std::vector<double> fallback, size_t min_size, size_t max_size, double lo,
                              double hi) const;
  std::vector<std::string> texts(const std::string& key, std::vector<std::string> fallback) const;
  // The elements of an array field, each as a reader of its own object; empty (and the problem
  // recorded) when the field is not an array.
  std::vector<JsonReader> objects(const std::string& key) const;
  JsonReader object(const std::string& key) const;

  // Keys the format does not know are typos, not extensions: say so.
  void only(const std::set<std::string>& known) const;

  const std::string& path() const { return path_; }
  std::string* error_sink() const { return error_; }

 private:
  const nlohmann::json& j_;
  std::string path_;
  std::string* error_;
};

}  // namespace shadelab
