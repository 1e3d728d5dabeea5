#pragma once
// A fragment shader rewritten so that one draw renders it for several values of some vec3 or vec4
// uniforms (the grader's lights: a position, a colour): the student's `main` runs once per value set, each run's colour
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
//
// With a census, the program also writes, for every run, whether its colour holds a NaN or an
// infinity: outputs after the runs' own, two runs each, (NaN, infinity) of run 2j in (R, G) and of
// run 2j + 1 in (B, A), as 0 or 1. The test reads the float's bits (an exponent of all ones, and a
// mantissa for NaN) with integer arithmetic and no branch, so it cannot be folded the way float
// algebra can, and a branch on the colour would stop `invariant` from reaching the arithmetic
// behind it (docs/grading.md). A target clears these outputs to zero; a multisampled one resolves
// each to nonzero where any sample held a flag.
#include <string>
#include <string_view>
#include <vector>

#include "core/expected.h"
#include "shader/shader_source.h"

namespace shadelab::shader {

inline constexpr const char* kVariantCount = "shadelab_variant_count";  // uniform int: how many runs

// The uniform array that holds `name`'s value for each run ("shadelab_variant_" + name).
std::string variant_uniform(std::string_view name);

// Outputs a program with `runs` runs writes: a colour each, and with a census one for every two runs.
struct VariantOutputs {
  int colours = 0, census = 0;
  int total() const { return colours + census; }
};
VariantOutputs variant_outputs(int runs, bool census);

// invalid_argument, saying why, when one pass cannot give what separate passes give: with more
// than one run, a `discard` or gl_FragDepth (one decision for every run) or a global the runs could
// share (a variable outside main, written by one run and read by the next); more than one output or
// an array of them, a name declared otherwise than `uniform [precision] vec3|vec4 NAME;` in the fragment
// shader or used by the vertex shader, GLSL ES 1.00 (one output, no integer bits), or more outputs
// than `max_outputs`, or a `#define` (it would apply to the code appended). One run with no names
// is the census alone.
Expected<std::string> with_uniform_variants(const UnwrappedSource& vertex, const UnwrappedSource& fragment,
                                            const std::vector<std::string>& names, int runs, int max_outputs, bool census = false);

}  // namespace shadelab::shader
