#include "core/client_json.h"

namespace shadelab {

namespace {

struct Shape {
  size_t depth = 0;   // the deepest nesting of arrays and objects
  size_t values = 0;  // an upper bound of the values: each opening bracket and each comma opens one
};

// One pass over the bytes outside strings. Exact for valid JSON; for anything else the parse
// that follows refuses it anyway.
Shape shape_of(std::string_view text, const JsonBudget& budget) {
  Shape shape;
  size_t depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
      continue;
    }
    switch (c) {
      case '"': in_string = true; break;
      case '[':
      case '{':
        ++shape.values;
        if (++depth > shape.depth) shape.depth = depth;
        if (shape.depth > budget.max_depth) return shape;  // no need to read on
        break;
      case ']':
      case '}':
        if (depth > 0) --depth;
        break;
      case ',': ++shape.values; break;
      default: break;
    }
  }
  return shape;
}

}  // namespace

Status check_json_budget(std::string_view text, std::string_view what, const JsonBudget& budget) {
  const Shape shape = shape_of(text, budget);
  if (shape.depth > budget.max_depth)
    return make_error(ErrorCode::invalid_argument, std::string(what) + " nests arrays and objects more than " +
                                                        std::to_string(budget.max_depth) + " levels deep; the limit is " +
                                                        std::to_string(budget.max_depth));
  if (shape.values > budget.max_values)
    return make_error(ErrorCode::payload_too_large, std::string(what) + " holds about " + std::to_string(shape.values) +
                                                         " JSON values; the limit is " + std::to_string(budget.max_values));
  return Ok{};
}

Expected<nlohmann::json> parse_client_json(std::string_view text, std::string_view what, const JsonBudget& budget) {
  if (auto within = check_json_budget(text, what, budget); !within) return within.take_error();
  nlohmann::json parsed = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (parsed.is_discarded()) return make_error(ErrorCode::invalid_argument, std::string(what) + " is not valid JSON");
  return parsed;
}

std::string describe_client_value(const nlohmann::json& value) {
  if (value.is_array()) return "an array of " + std::to_string(value.size());
  if (value.is_object()) return "an object of " + std::to_string(value.size()) + " fields";
  std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (text.size() <= 40) return text;
  size_t cut = 37;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 character
  return text.substr(0, cut) + "...";
}

}  // namespace shadelab
