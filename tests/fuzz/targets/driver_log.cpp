// shader::parse_driver_log on a driver's info log (Mesa, NVIDIA, ANGLE formats) for a student's
// file. Input: a selector byte, the shader file, the separator, the log. Invariants: nothing
// thrown, every diagnostic of the stage asked for, with a known severity, located inside the file
// or not at all.
#include <algorithm>
#include <string>

#include "fuzz_check.h"
#include "shader/driver_log.h"

namespace {
// Lines as the student's editor counts them: LF, CRLF and a lone CR each end one.
int lines_in(const std::string& text) {
  int lines = 1;
  for (size_t i = 0; i < text.size(); ++i) lines += text[i] == '\n' || (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n'));
  return lines;
}

void check(const std::vector<shadelab::Diagnostic>& diagnostics, std::string_view stage, int file_lines) {
  for (const auto& d : diagnostics) {
    FUZZ_CHECK(d.stage == stage);
    FUZZ_CHECK(d.severity == "error" || d.severity == "warning");
    FUZZ_CHECK(d.line >= 0 && d.line <= file_lines);
    FUZZ_CHECK(d.column >= 0);
    FUZZ_CHECK(d.line > 0 || d.column == 0);
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  shadelab::fuzz::InputReader input(data, size);
  const auto stage = (input.byte() & 1) ? shadelab::shader::Stage::fragment : shadelab::shader::Stage::vertex;
  const shadelab::shader::ShaderFile file{"phong_frag.js", std::string(input.part())};
  const std::string log(input.rest());
  const std::string_view stage_name = shadelab::shader::to_string(stage);
  auto source = shadelab::shader::unwrap(file, stage);
  if (source) check(shadelab::shader::parse_driver_log(log, stage_name, file.name, &*source), stage_name, lines_in(file.text));
  check(shadelab::shader::parse_driver_log(log, "link", file.name, nullptr), "link", 0);
  return 0;
}
