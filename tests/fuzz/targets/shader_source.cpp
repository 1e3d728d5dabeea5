// shader::unwrap, as the HTTP edge and the workers call it on a student's file (raw GLSL or the
// JS module the page imports). Invariant: the line map sends every GLSL line, and every location
// a diagnostic may carry, back to a line and column inside the student's file. Then the grader's
// rewrites of what unwrapped (shader/invariant_outputs.h, shader/uniform_variants.h): every line
// of the student's GLSL stays where it was.
#include <algorithm>
#include <tuple>
#include <string>

#include "fuzz_check.h"
#include "shader/invariant_outputs.h"
#include "shader/shader_source.h"
#include "shader/uniform_variants.h"

namespace {

using shadelab::shader::LineOrigin;

struct FileShape {
  std::vector<size_t> line_lengths;  // bytes per line, without the '\n'
  int lines() const { return static_cast<int>(line_lengths.size()); }
  bool holds(int line, int column) const {
    return line >= 1 && line <= lines() && column >= 1 && static_cast<size_t>(column) <= line_lengths[line - 1] + 1;
  }
};

// Lines as the student's editor shows them: LF, CRLF and a lone CR each end one.
FileShape shape_of(const std::string& text) {
  FileShape shape{{0}};
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n' || (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n'))) shape.line_lengths.push_back(0);
    else ++shape.line_lengths.back();
  return shape;
}

void check_line_map(const shadelab::shader::UnwrappedSource& source, const FileShape& file) {
  FUZZ_CHECK(source.lines.size() == 1 + static_cast<size_t>(std::count(source.glsl.begin(), source.glsl.end(), '\n')));
  for (size_t i = 0; i < source.lines.size(); ++i) {
    FUZZ_CHECK(file.holds(source.lines[i].file_line, source.lines[i].file_column));
    if (i > 0) FUZZ_CHECK(source.lines[i].file_line >= source.lines[i - 1].file_line);
  }
  // Every character of the GLSL lands on a character of the file (or just past its line's end).
  int glsl_line = 1, glsl_column = 1;
  for (char c : source.glsl) {
    if ((static_cast<unsigned char>(c) & 0xC0) == 0x80) continue;
    const LineOrigin at = source.locate(glsl_line, glsl_column);
    FUZZ_CHECK(at.file_column > 0 && file.holds(at.file_line, at.file_column));
    if (c == '\n') ++glsl_line, glsl_column = 1;
    else ++glsl_column;
  }
  // Drivers name lines and columns past either end: each is in the file, or unknown (0).
  const int n = static_cast<int>(source.lines.size());
  for (int line : {-1, 0, 1, n / 2, n, n + 1, 1 << 30})
    for (int column : {-1, 0, 1, 7, 1 << 30}) {
      const LineOrigin at = source.locate(line, column);
      FUZZ_CHECK((at.file_line == 0 && at.file_column == 0) || file.holds(at.file_line, std::max(at.file_column, 1)));
      FUZZ_CHECK(line >= 1 || at.file_line == 0);
    }
}

size_t lines_in(std::string_view s) { return static_cast<size_t>(std::count(s.begin(), s.end(), '\n')); }

void check_rewrites(const shadelab::shader::UnwrappedSource& source, shadelab::shader::Stage stage) {
  FUZZ_CHECK(lines_in(shadelab::shader::with_invariant_outputs(source.glsl, stage)) == lines_in(source.glsl));
  if (stage != shadelab::shader::Stage::fragment) return;
  // Two lights, with and without the census; the census alone (one run).
  const std::vector<std::string> light = {"uLightPosition"};
  for (const auto& [names, runs, census] : {std::tuple{light, 2, false}, std::tuple{light, 2, true}, std::tuple{std::vector<std::string>{}, 1, true}}) {
    auto one_pass = shadelab::shader::with_uniform_variants(shadelab::shader::UnwrappedSource{}, source, names, runs, 8, census);
    if (!one_pass) {
      FUZZ_CHECK(!one_pass.error().message.empty());
      continue;
    }
    const size_t epilogue = one_pass->rfind("\n// One pass for every light");
    FUZZ_CHECK(epilogue != std::string::npos);
    FUZZ_CHECK(lines_in(std::string_view(*one_pass).substr(0, epilogue)) == lines_in(source.glsl));
    FUZZ_CHECK((one_pass->find("shadelab_census_0", epilogue) != std::string::npos) == census);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  shadelab::fuzz::InputReader input(data, size);
  const std::uint8_t selector = input.byte();
  const auto stage = (selector & 1) ? shadelab::shader::Stage::fragment : shadelab::shader::Stage::vertex;
  const shadelab::shader::ShaderFile file{(selector & 2) ? "phong_frag.js" : "", std::string(input.rest())};
  const FileShape shape = shape_of(file.text);
  auto unwrapped = shadelab::shader::unwrap(file, stage);
  if (unwrapped) {
    check_line_map(*unwrapped, shape);
    check_rewrites(*unwrapped, stage);
    FUZZ_CHECK(unwrapped->glsl.find('\0') == std::string::npos);
  } else {
    for (const auto& d : unwrapped.error().diagnostics) FUZZ_CHECK(d.line == 0 || shape.holds(d.line, std::max(d.column, 1)));
  }
  return 0;
}
