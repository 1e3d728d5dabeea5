#pragma once
// GLSL with every shader output redeclared `invariant`, for a render that must follow IEEE
// arithmetic. Mesa's optimiser rewrites algebra it may assume finite (x - x -> 0, 0 * x -> 0), so
// `normalize(n - n)` gives 0 on llvmpipe where IEEE arithmetic, and the GPU behind the student's
// browser, give NaN (measured: docs/grading.md). Mesa does not rewrite what an invariant output
// depends on, so the same program, its outputs invariant, shows the NaN.
//
// `invariant NAME;` goes right after each global `out` declaration's semicolon, on the same line,
// so every line keeps its number; a vertex shader's gl_Position joins the first. A fragment shader
// may not use `#pragma STDGL invariant(all)`, hence the redeclarations.
#include <string>
#include <string_view>

#include "shader/shader_source.h"

namespace shadelab::shader {

// `glsl` unchanged when it declares no output at global scope.
std::string with_invariant_outputs(std::string_view glsl, Stage stage);

}  // namespace shadelab::shader
