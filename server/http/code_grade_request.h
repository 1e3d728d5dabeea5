#pragma once
// POST /api/grade with code: the fields read into the road's client-shaped request
// (road/code_request.h). A render's fields (`width`, `height`, `frames`, `degreesPerFrame`, `msaa`,
// `uniforms`, `mesh`, `fit`), the student's shaders or a `preset`, what they are graded against
// (`reference`, a checkpoint or an alias of one, or `referenceVertex` + `referenceFragment`), the
// tolerance (`threshold`, `maxFailingFraction`, `spatialTolerance`, `maxScore`), and `format`, the
// result's: json or gradescope. Fields only: what the course makes of them is the road's.
#include <string>
#include <vector>

#include "core/expected.h"
#include "http/api_request.h"
#include "road/code_request.h"

namespace shadelab::http {

struct ParsedCodeGrade {
  road::CodeRequest request;
  std::string result_format = "json";
  std::vector<std::string> warnings;
};

Expected<ParsedCodeGrade> parse_code_grade(const RawRequest& raw, const Limits& limits);

}  // namespace shadelab::http
