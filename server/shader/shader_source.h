#pragma once
// Shader input as students have it: raw GLSL, or the JS module their page imports
// (`export default \`#version 300 es ...\`` or a quoted string), possibly with a BOM and CRLF line
// ends. Unwrapping keeps a line map so diagnostics point into the student's own file.
#include <string>
#include <vector>

#include "core/expected.h"

namespace shadelab::shader {

enum class Stage { vertex, fragment };
std::string_view to_string(Stage stage);

struct ShaderFile {
  std::string name;  // what the student calls it ("phong_frag.js"); may be empty
  std::string text;  // the file's bytes
};

// Where a GLSL line starts in the student's file.
struct LineOrigin {
  int file_line = 1;    // 1-based
  int file_column = 1;  // 1-based column of the GLSL line's first character
};

// From (glsl_line, glsl_column) on, each GLSL character comes from the next file character, up
// to the next run: escapes (`\n`, `\u00e9`) and line continuations start new runs.
struct MappedRun {
  int glsl_line = 1, glsl_column = 1;  // 1-based; columns count characters, not bytes
  LineOrigin origin;
};

struct UnwrappedSource {
  std::string glsl;                 // what the driver compiles
  std::vector<LineOrigin> lines;    // one per GLSL line: where it starts in the file
  std::vector<MappedRun> runs;      // ordered by GLSL position
  bool from_js_module = false;
  std::vector<std::string> warnings;

  // Maps a GLSL (line, column), both 1-based (column 0 = unknown), into the file. A line before
  // the first is unknown ({0, 0}); one past the last is the last line; a column outside its line
  // is unknown (0).
  LineOrigin locate(int glsl_line, int glsl_column) const;
};

struct SourceLimits {
  size_t max_bytes = 64 * 1024;
};

// Unwraps and checks what WebGL2 itself checks before the driver sees it: valid UTF-8, no NUL,
// `#version 300 es` on the first line. Errors carry a Diagnostic located in the file.
Expected<UnwrappedSource> unwrap(const ShaderFile& file, Stage stage, const SourceLimits& limits = {});

}  // namespace shadelab::shader
