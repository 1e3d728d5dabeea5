#pragma once
// WebGL 2's own shader rules, between the source checks and the driver. Mesa follows plain
// OpenGL ES; the student's browser adds the WebGL 2 specification's rules on top ("Differences
// Between WebGL and OpenGL ES 3.0"), and for GLSL ES 1.00 shaders the loop and indexing limits of
// GLSL ES 1.00 Appendix A. A grader that compiled what the browser refused would grade a program
// the student never saw run. docs/webgl-rules.md lists every rule with its source.
//
// ShadeLab's front end decides, not the driver: each stage is compiled by glslang as GLSL ES,
// every error it finds refuses the stage, and the pair is linked by shader/link_rules.h. The
// driver compiles only what the browser would run (a GPU driver may accept more, or refuse with
// a log that names nothing).
#include <string>
#include <vector>

#include "core/error.h"
#include "core/expected.h"
#include "shader/glsl_facts.h"
#include "shader/shader_source.h"
#include "shader/stand_in_names.h"

namespace shadelab::shader {

struct WebglChecked {
  GlslFacts vertex, fragment;
  std::vector<Diagnostic> warnings;   // the browser's warnings: extensions it does not support
  std::vector<StandIn> renamed;       // names the browser runs and glslang or the driver reserve
};

// Checks both stages and what links them; then rewrites each stage's GLSL where WebGL's defaults
// are not the driver's, every line keeping its number:
//  - a stage that declares a uniform block gets `layout(std140) uniform;` (WebGL's only layout,
//    and its default; the driver's default is `shared`, so a block declared std140 in one stage
//    and without a layout in the other would not link);
//  - an extension the browser does not support, enabled (not required), is left out, as the
//    browser goes on without it; so are `#extension all` and `disable`, and a hint `#pragma`
//    before an extension the driver still gets (Mesa counts it as code, the browser does not);
//  - GLSL ES 1.00: `invariant gl_FragCoord;` where the vertex shader does not declare gl_Position
//    invariant (the browser binds it only where gl_FragCoord is read; Mesa everywhere);
//  - an `#if` in literals that glslang cannot evaluate (`0 && 1/0`) becomes its value;
//  - an empty declaration right after a label (`case 0: int;`) loses its words (`case 0: ;`),
//    which NVIDIA's driver needs to see a statement there.
// A stage's rule -> compile_failed, a rule between the stages -> link_failed; each diagnostic in
// the student's file, in the browser's words.
Expected<WebglChecked> apply_webgl_rules(UnwrappedSource& vertex, UnwrappedSource& fragment,
                                        const ShaderFile& vertex_file, const ShaderFile& fragment_file);

}  // namespace shadelab::shader
