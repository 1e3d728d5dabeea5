#pragma once
// A fragment shader rewritten so that one draw renders it for several values of some vec3
// uniforms (the grader's lights): the student's `main` runs once per value set, each run's colour
// to an output of its own (location k for set k), so the geometry is rasterised once for every
// light (docs/grading.md, "One pass for every light").
//
// The runs are a loop whose count is a uniform, not unrolled code: unrolled, the compiler would
// share the runs' common work (the normal's normalisation, the material's products), and sharing
// changes whether it fuses a multiply with an add, so the last bit of a colour. In a loop each run
// computes what a pass of its own computes, and the frames are the same bytes (tested).
//
// Lines stay where they are: `main` is renamed in place, a light's `uniform` and the output's
// `out` are blanked, and the new `main` follows the student's code.
#include <string>
#include <string_view>
#include <vector>

#include "core/expected.h"
#include "shader/shader_source.h"

namespace shadelab::shader {

inline constexpr const char* kVariantCount = "shadelab_variant_count";  // uniform int: how many runs

// The uniform array that holds `name`'s value for each run ("shadelab_variant_" + name).
std::string variant_uniform(std::string_view name);

// invalid_argument, saying why, when one pass cannot give what separate passes give: a `discard`
// or gl_FragDepth (one decision for every run), a global the runs could share (a variable outside
// main, written by one run and read by the next), more than one output or an array of them, a
// name declared otherwise than `uniform [precision] vec3 NAME;` in the fragment shader or used by
// the vertex shader, GLSL ES 1.00, or more runs than `max_outputs`.
Expected<std::string> with_uniform_variants(const UnwrappedSource& vertex, const UnwrappedSource& fragment,
                                            const std::vector<std::string>& names, int runs, int max_outputs);

}  // namespace shadelab::shader
