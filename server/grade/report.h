#pragma once
// Grade results as JSON, ShadeLab's own and Gradescope's results.json.
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "grade/grader.h"

namespace shadelab::grade {

nlohmann::json to_json(const GradeResult& result, const std::string& checkpoint);
// A submission that could not be graded (does not compile, hangs, crashes): score 0, the reason.
nlohmann::json failed_submission(const Error& error, const std::string& checkpoint, double max_score);
// Gradescope's results.json: score, execution_time, output, tests[] (name, score, max_score,
// status, output, visibility).
nlohmann::json to_gradescope(const nlohmann::json& result, double execution_seconds);

}  // namespace shadelab::grade
