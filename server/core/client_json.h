#pragma once
// JSON a client wrote (a request body, a multipart field, a glTF's JSON chunk), read within a
// budget checked on the bytes before nlohmann builds a value: how deep arrays and objects nest and
// how many values there are. nlohmann's parser and destructor are iterative, but dump(), copies
// and == recurse, so a body nesting 200,000 arrays would overflow the stack of whichever handler
// touched it later; and a 16 MiB body of `[],` is a tree of millions of allocations.
#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/expected.h"

namespace shadelab {

struct JsonBudget {
  // ShadeLab's deepest document is a glTF's (about 8 levels); a scene is 6, a request 3.
  size_t max_depth = 32;
  // Arrays, objects and scalars together; a request holds tens, a glTF's JSON thousands.
  size_t max_values = size_t{1} << 20;
};

// Ok when `text` fits the budget: a 400 when it nests too deep, a 413 when it holds too many values.
Status check_json_budget(std::string_view text, std::string_view what, const JsonBudget& budget = {});

// The text parsed, or a 400 (too deep, not JSON) or a 413 (too many values) naming `what`
// ("the request body", "the glTF's JSON"), never echoing the client's text.
Expected<nlohmann::json> parse_client_json(std::string_view text, std::string_view what, const JsonBudget& budget = {});

// What an error may say of a client's value: its type, and a scalar's text cut to 40 bytes
// (never an array's or object's contents, which may be megabytes or thousands of levels deep).
std::string describe_client_value(const nlohmann::json& value);

}  // namespace shadelab
