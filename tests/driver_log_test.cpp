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

// A driver quotes the student's identifier in its message; a shader may be 64 KiB, so may the
// identifier. std::regex, which read these lines once, recursed per character and overflowed the
// worker's stack on such a line; each format is read left to right now.
TEST(DriverLogTest, AMessageQuotingAHugeIdentifierIsOneDiagnostic) {
  const std::string name(200000, 'a');
  for (const std::string& line : {"0:12(5): error: `" + name + "' undeclared", "0(12) : error C1008: undefined variable \"" + name + "\"",
                                   "ERROR: 0:12: '" + name + "' : undeclared identifier", "error: " + name}) {
    const auto d = shader::parse_driver_log(line + "\r\n", "fragment", "phong_frag.js", nullptr);
    ASSERT_EQ(d.size(), 1u) << line.substr(0, 20);
    EXPECT_EQ(d[0].severity, "error");
    EXPECT_NE(d[0].message.find(name), std::string::npos);
    EXPECT_LT(d[0].message.size(), line.size()) << "read as a located message, its prefix taken off";
    EXPECT_NE(d[0].message.back(), '\r') << "the CR of a CRLF log is not message text";
  }
}
