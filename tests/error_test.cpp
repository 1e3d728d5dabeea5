#include <gtest/gtest.h>

#include <set>

#include "core/error.h"
#include "http/problem.h"
#include "worker/result.h"

using shadelab::ErrorCode;
using namespace shadelab;

TEST(ErrorCodeTest, EveryCodeHasExactlyOneRowWithADistinctNameStatusAndTitle) {
  std::set<std::string_view> names;
  const auto codes = error_codes();
  ASSERT_EQ(codes.size(), static_cast<size_t>(ErrorCode::driver_refused) + 1) << "a code without a row, or a row too many (the last enumerator here)";
  for (size_t i = 0; i < codes.size(); ++i) {
    const auto& row = codes[i];
    EXPECT_EQ(static_cast<size_t>(row.code), i) << row.name << ": the table must follow the enum's order";
    EXPECT_TRUE(names.insert(row.name).second) << "duplicate name " << row.name;
    EXPECT_GE(row.status, 400) << row.name;
    EXPECT_LT(row.status, 600) << row.name;
    EXPECT_FALSE(row.title.empty()) << row.name;
    EXPECT_EQ(error_code_named(row.name), row.code);
  }
  EXPECT_EQ(to_string(ErrorCode::compile_failed), "compile_failed");
  EXPECT_EQ(http_status(ErrorCode::compile_failed), 422);
  EXPECT_FALSE(error_code_named("no_such_code"));
}

TEST(ErrorCodeTest, WhatASubmissionCausesIsItsGradeAndWhatTheServiceCausesIsNot) {
  for (const auto code : {ErrorCode::compile_failed, ErrorCode::link_failed, ErrorCode::render_timeout, ErrorCode::compile_crashed,
                          ErrorCode::out_of_memory, ErrorCode::missing_version, ErrorCode::shader_source_invalid})
    EXPECT_TRUE(info(code).submission_caused) << to_string(code);
  for (const auto code : {ErrorCode::queue_full, ErrorCode::not_ready, ErrorCode::invalid_argument, ErrorCode::mesh_parse_failed,
                          ErrorCode::worker_protocol, ErrorCode::view_transform_unavailable})
    EXPECT_FALSE(info(code).submission_caused) << to_string(code);
  EXPECT_TRUE(info(ErrorCode::queue_full).retry_later);
  EXPECT_FALSE(info(ErrorCode::compile_failed).retry_later);
}

// Every code a worker can raise reaches the client with its own code and status: through the
// worker's answer, then problem+json.
TEST(ErrorCodeTest, EveryCodeRoundTripsThroughTheWorkerWireAndProblemJson) {
  for (const auto& row : error_codes()) {
    Error sent{row.code, "what went wrong", {{"fragment", "phong_frag.js", 12, 5, "error", "`x' undeclared"}}, "0:12(5): error: ..."};
    auto received = worker::result_from<worker::CompileResult>(worker::answer(sent));
    ASSERT_FALSE(received.ok()) << row.name;
    const Error& e = received.error();
    EXPECT_EQ(e.code, row.code) << row.name << " arrived as " << to_string(e.code);
    EXPECT_EQ(e.message, sent.message);
    EXPECT_EQ(e.driver_log, sent.driver_log);
    ASSERT_EQ(e.diagnostics.size(), 1u);
    EXPECT_EQ(e.diagnostics[0].format(), sent.diagnostics[0].format());

    const auto p = http::problem(e, "/api/render");
    EXPECT_EQ(p["code"], row.name);
    EXPECT_EQ(p["status"], row.status);
    EXPECT_EQ(p["title"], row.title);
    EXPECT_EQ(p["type"], "urn:shadelab:error:" + std::string(row.name));
    EXPECT_EQ(p["diagnostics"][0]["line"], 12);
  }
}

TEST(ErrorCodeTest, AnUnknownCodeFromAWorkerIsAProtocolErrorNotAGuess) {
  const auto e = nlohmann::json{{"code", "flux_capacitor"}, {"message", "?"}}.get<Error>();
  EXPECT_EQ(e.code, ErrorCode::worker_protocol);
  EXPECT_NE(e.message.find("flux_capacitor"), std::string::npos);
}

TEST(DiagnosticTest, FormatsLikeACompiler) {
  shadelab::Diagnostic d{"fragment", "phong_frag.js", 12, 5, "error", "`foo' undeclared"};
  EXPECT_EQ(d.format(), "phong_frag.js:12:5: error: `foo' undeclared");
  d.column = 0;
  EXPECT_EQ(d.format(), "phong_frag.js:12: error: `foo' undeclared");
}
