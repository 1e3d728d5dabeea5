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

// The two languages a WebGL 2 context compiles: GLSL ES 3.00 (`#version 300 es` on the first
// line) and GLSL ES 1.00 (`#version 100`, or no #version at all), as students copy it from
// WebGL 1 tutorials (`attribute`, `varying`, `gl_FragColor`).
enum class GlslVersion { es100, es300 };
std::string_view to_string(GlslVersion version);  // "GLSL ES 1.00", "GLSL ES 3.00"

struct UnwrappedSource {
  std::string glsl;                 // what the driver compiles
  GlslVersion version = GlslVersion::es300;
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
// a #version only on the first line and only one WebGL 2 compiles (300 es or 100). Errors carry a Diagnostic located in the file.
Expected<UnwrappedSource> unwrap(const ShaderFile& file, Stage stage, const SourceLimits& limits = {});

// WebGL 2 links only shaders of one version: link_failed saying which stage is which (the
// driver's "all shaders must use same shading language version" does not), located at the
// fragment shader's first line.
Status check_same_version(const UnwrappedSource& vertex, const UnwrappedSource& fragment, const ShaderFile& fragment_file);

}  // namespace shadelab::shader
