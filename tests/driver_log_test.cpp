#include <gtest/gtest.h>

#include "shader/driver_log.h"

using namespace shadelab;

TEST(DriverLogTest, MesaLinesAreLocatedThroughTheLineMap) {
  auto src = shader::unwrap({"phong_frag.js", "// header\nexport default `#version 300 es\nvoid main() {\n  x;\n}\n`"},
                            shader::Stage::fragment);
  ASSERT_TRUE(src) << src.error().format();
  const auto d = shader::parse_driver_log("0:3(3): error: `x' undeclared\n0:3(3): warning: statement has no effect\n",
                                          "fragment", "phong_frag.js", &*src);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].line, 4);
  EXPECT_EQ(d[0].column, 3);
  EXPECT_EQ(d[0].severity, "error");
  EXPECT_EQ(d[0].message, "`x' undeclared");
  EXPECT_EQ(d[1].severity, "warning");
  EXPECT_EQ(d[0].format(), "phong_frag.js:4:3: error: `x' undeclared");
}

TEST(DriverLogTest, NvidiaAndAngleFormatsAreUnderstood) {
  const auto nv = shader::parse_driver_log("0(7) : error C1008: undefined variable \"x\"", "vertex", "v.js", nullptr);
  ASSERT_EQ(nv.size(), 1u);
  EXPECT_EQ(nv[0].severity, "error");
  const auto angle = shader::parse_driver_log("ERROR: 0:7: 'x' : undeclared identifier", "vertex", "v.js", nullptr);
  ASSERT_EQ(angle.size(), 1u);
  EXPECT_EQ(angle[0].severity, "error");
  EXPECT_EQ(angle[0].line, 0);  // no source map given: not located
}

TEST(DriverLogTest, UnlocatedLinkMessagesAreKept) {
  const auto d = shader::parse_driver_log("error: fragment shader input `vColor' has no matching output\n", "link", "", nullptr);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].stage, "link");
  EXPECT_EQ(d[0].line, 0);
  EXPECT_NE(d[0].message.find("vColor"), std::string::npos);
}
