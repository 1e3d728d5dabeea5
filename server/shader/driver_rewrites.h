#pragma once
// What a stage's GLSL becomes for the driver where the browser and the driver read one program
// differently: the same program, every line in its place (the driver's line numbers map back to
// the student's file). shader/webgl_rules.h decides when each applies.
#include <string>

#include "shader/glsl_facts.h"

namespace shadelab::shader {

// `layout(std140) uniform;` after the directives (#version, #extension), then `#line` gives the
// next line the number it had: WebGL's only block layout is the driver's default too.
void default_to_std140(std::string& glsl, const GlslFacts& facts);

// `case 0: int;` as a label's last statement becomes `case 0: ;` (NVIDIA's driver needs a
// statement there; the browser takes the empty declaration as one).
void blank_empty_declarations_after_labels(std::string& glsl, const GlslFacts& facts);

// A hint `#pragma` before line `last_extension` (an extension the driver still gets) left out.
void blank_hints_before(std::string& glsl, const GlslFacts& facts, int last_extension);

}  // namespace shadelab::shader
