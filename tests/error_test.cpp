#include <gtest/gtest.h>

#include <set>

#include "core/error.h"

using shadelab::ErrorCode;

TEST(ErrorCodeTest, EveryCodeHasADistinctNameAndAnHttpStatus) {
  std::set<std::string_view> names;
  for (int i = 0; i <= static_cast<int>(ErrorCode::view_transform_unavailable); ++i) {
    const auto code = static_cast<ErrorCode>(i);
    const auto name = shadelab::to_string(code);
    EXPECT_TRUE(names.insert(name).second) << "duplicate name " << name;
    EXPECT_GE(shadelab::http_status(code), 400);
    EXPECT_LT(shadelab::http_status(code), 600);
  }
  EXPECT_EQ(shadelab::to_string(ErrorCode::compile_failed), "compile_failed");
  EXPECT_EQ(shadelab::http_status(ErrorCode::compile_failed), 422);
}

TEST(DiagnosticTest, FormatsLikeACompiler) {
  shadelab::Diagnostic d{"fragment", "phong_frag.js", 12, 5, "error", "`foo' undeclared"};
  EXPECT_EQ(d.format(), "phong_frag.js:12:5: error: `foo' undeclared");
  d.column = 0;
  EXPECT_EQ(d.format(), "phong_frag.js:12: error: `foo' undeclared");
}
