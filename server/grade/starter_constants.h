#pragma once
// A failing submission that changed a number the course's starter sets ("float specularAlpha =
// 6.0;") is told so in those terms: "your shader's exponent is 0.6; the course's starter uses 6.0".
// Read from the source alone (comments skipped): no render, and a name the student kept.
#include <string>
#include <vector>

#include "grade/grade_spec.h"

namespace shadelab::grade {

struct ConstantFinding {
  std::string variable;  // specularAlpha
  double value = 0;      // the student's: 0.6
  std::string message;
};

// The first value each constant is given in `source` (a declaration's initialiser or an
// assignment of a literal), where it differs from the starter's.
std::vector<ConstantFinding> changed_starter_constants(const std::vector<StarterConstant>& constants, const std::string& source);

// The stripped text: comments replaced by spaces, so a commented-out line is not read.
std::string without_comments(const std::string& source);

}  // namespace shadelab::grade
